"""The folder name of a workflow's cells (experiments/*/Snakefile): a hash of
what a cell's result depends on, the scene text, the options and the weavelab
program that runs it, so that a rerun reruns the cells of a changed scene, new
options or a rebuilt program, and only those."""
import hashlib


def cell_key(scene, options, program="build/weavelab"):
    """16 hex digits of sha256(scene file bytes, options, program file bytes)."""
    digest = hashlib.sha256()
    for path in (scene, program):
        with open(path, "rb") as f:
            digest.update(f.read())
        digest.update(b"\0")
    digest.update(options.encode())
    return digest.hexdigest()[:16]
