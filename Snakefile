# Every study of weavelab in one workflow (experiments/README.md): includes each
# experiments/<study>/Snakefile, asks for every study's RESULTS.md and writes the
# index experiments/INDEX.md from them (and the results-index block of README.md).
# From the repository root, after tools/setup.sh has built build/:
#   snakemake -n                                   what would run, every study
#   snakemake --cores 2                            every study, then the index
#   snakemake --cores 2 --config studies=cusick,stability   a chosen set
#   snakemake --cores 2 stability_all              one study
#   snakemake --cores 1 index                      only the index
# Each study's own config is nested under its name (experiments/<study>/config.yaml).
import glob
import os

# The studies in the order of the index; a study folder not listed here is
# appended. A listed study without a Snakefile yet is shown as not yet run.
STUDY_ORDER = ["main_job", "calibration", "homogenization", "diagnosis", "error_budget", "accuracy", "trajectory_fit",
               "cusick", "obstacles", "cantilever", "slide_pull", "knits", "pattern_study", "stability",
               "work_precision", "fidelity", "published_code", "speed", "scale", "determinism", "mixed"]
STUDIES_FOUND = sorted(os.path.basename(os.path.dirname(p)) for p in glob.glob("experiments/*/Snakefile"))
STUDIES_ALL = STUDY_ORDER + [s for s in STUDIES_FOUND if s not in STUDY_ORDER]


def chosen_studies(value):
    """The studies of --config studies=a,b (default: all that have a Snakefile)."""
    if value is None:
        return [s for s in STUDIES_ALL if s in STUDIES_FOUND]
    names = value if isinstance(value, list) else [v.strip() for v in str(value).split(",") if v.strip()]
    unknown = [s for s in names if s not in STUDIES_FOUND]
    if unknown:
        raise ValueError(f"config key 'studies': no study {', '.join(unknown)}; "
                         f"expected a comma-separated list of {', '.join(STUDIES_FOUND)}")
    return names


STUDIES_CHOSEN = chosen_studies(config.get("studies"))


rule all:
    input: "experiments/INDEX.md"


for _study in STUDIES_FOUND:
    include: f"experiments/{_study}/Snakefile"


def study_results(study):
    """The RESULTS.md a study writes (its config key `results`)."""
    section = config.get(study)
    if isinstance(section, dict) and "results" in section:
        return section["results"]
    return f"experiments/{study}/RESULTS.md"


INDEX_COMMAND = ("/usr/bin/python3 experiments/common/study_index.py experiments/INDEX.md {params.results} "
                 "--readme README.md")


rule studies_then_index:
    input: [study_results(s) for s in STUDIES_CHOSEN]
    output: "experiments/INDEX.md"
    params: results=[study_results(s) for s in STUDIES_ALL]
    shell: INDEX_COMMAND


# `snakemake --cores 1 index`: the index alone, from the RESULTS.md files as they are
# (no output file, so that no study is rerun for it).
rule index:
    params: results=[study_results(s) for s in STUDIES_ALL]
    shell: INDEX_COMMAND
