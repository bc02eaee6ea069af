"""Runs a ```python block of README.md as a user would from the repository:
in a scratch folder that sees the repository's models/, with the package importable.
What the README says the block prints ("It prints `...`" after the block) must be
a line it printed.
    run_python_snippet.py SNIPPET SOURCE_DIR
Exits 77 (CTest: skipped) when the HDM05 data the snippet reads is absent."""
import contextlib
import io
import os
import pathlib
import re
import runpy
import sys
import tempfile

snippet, source = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
data = pathlib.Path(os.environ.get("ACTIONSTRING_DATA", source.parent / "shared" / "data")).resolve()
if not (data / "hdm05" / "train.tsv").is_file():
    print(f"SKIPPED: {data}/hdm05/train.tsv not found (set ACTIONSTRING_DATA)")
    sys.exit(77)
os.environ["ACTIONSTRING_DATA"] = str(data)

# The README's claims about this block: the text between its closing fence and the next fence.
index = int(re.search(r"_(\d+)$", snippet.stem).group(1))
readme = (source / "README.md").read_text(encoding="utf-8")
blocks = [m.end() for m in re.finditer(r"^```python\n.*?^```\n", readme, re.S | re.M)]
after = readme[blocks[index]:] if index < len(blocks) else ""
after = after[: after.find("```")] if "```" in after else after
claims = re.findall(r"It prints `([^`]*)`", after)

printed = io.StringIO()
with tempfile.TemporaryDirectory() as scratch:
    os.symlink(source / "models", pathlib.Path(scratch) / "models")
    os.chdir(scratch)
    with contextlib.redirect_stdout(printed):
        runpy.run_path(str(snippet), run_name="__main__")
    assert (pathlib.Path(scratch) / "hdm05.blob").stat().st_size > 0
output = printed.getvalue()
sys.stdout.write(output)
lines = output.splitlines()
for claim in claims:
    assert claim in lines, f"README.md says the snippet prints {claim!r}; it printed:\n{output}"
print(f"{len(claims)} printed line(s) the README quotes, each printed")
