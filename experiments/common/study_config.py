"""Reading a study's config values (experiments/README.md, "Configuration").

A value comes either from the study's config.yaml (YAML types: a list, an
int, a bool) or from `--config` on the command line, where Snakemake hands
every nested value over as a string ("yarn,fem", "3", "true"). These
functions accept both and name the key and the value when it is neither.
"""


class ConfigError(ValueError):
    pass


def as_list(value, key="value"):
    """A list of strings from a YAML list or a comma-separated string."""
    if isinstance(value, (list, tuple)):
        return [str(v).strip() for v in value]
    if isinstance(value, (str, int, float)):
        items = [v.strip() for v in str(value).split(",")]
        if any(not v for v in items):
            raise ConfigError(f"config key '{key}': got '{value}', expected a comma-separated list without empty items")
        return items
    raise ConfigError(f"config key '{key}': got {value!r}, expected a list or a comma-separated string")


def as_int(value, key="value"):
    try:
        if isinstance(value, bool) or (isinstance(value, float) and not value.is_integer()):
            raise ValueError
        return int(str(value).strip())
    except ValueError:
        raise ConfigError(f"config key '{key}': got '{value}', expected an integer") from None


def as_float(value, key="value"):
    try:
        if isinstance(value, bool):
            raise ValueError
        return float(str(value).strip())
    except ValueError:
        raise ConfigError(f"config key '{key}': got '{value}', expected a number") from None


def as_bool(value, key="value"):
    if isinstance(value, bool):
        return value
    text = str(value).strip().lower()
    if text in ("true", "yes", "1", "on"):
        return True
    if text in ("false", "no", "0", "off"):
        return False
    raise ConfigError(f"config key '{key}': got '{value}', expected true or false")


def study_config(config, study):
    """The study's part of the config, with the keys every study needs."""
    part = config.get(study)
    if not isinstance(part, dict):
        raise ConfigError(f"config: no section '{study}' (experiments/{study}/config.yaml nests every key under it)")
    for key in ("out", "results"):
        if key not in part:
            raise ConfigError(f"config key '{study}.{key}' is missing (experiments/{study}/config.yaml)")
    return part
