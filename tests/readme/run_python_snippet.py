"""Runs a ```python block of README.md as a user would from the repository:
in a scratch folder that sees the repository's models/, with the package importable.
    run_python_snippet.py SNIPPET SOURCE_DIR
Exits 77 (CTest: skipped) when the HDM05 data the snippet reads is absent."""
import os
import pathlib
import runpy
import sys
import tempfile

snippet, source = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
data = pathlib.Path(os.environ.get("ACTIONSTRING_DATA", source.parent / "shared" / "data")).resolve()
if not (data / "hdm05" / "train.tsv").is_file():
    print(f"SKIPPED: {data}/hdm05/train.tsv not found (set ACTIONSTRING_DATA)")
    sys.exit(77)
os.environ["ACTIONSTRING_DATA"] = str(data)
with tempfile.TemporaryDirectory() as scratch:
    os.symlink(source / "models", pathlib.Path(scratch) / "models")
    os.chdir(scratch)
    runpy.run_path(str(snippet), run_name="__main__")
    assert (pathlib.Path(scratch) / "hdm05.blob").stat().st_size > 0
