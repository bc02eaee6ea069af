"""`actionstring view` in a real browser: the page is self-contained, and
Debian's chromium, headless, loads it without a script error and draws every
canvas (the page's own pixel count, in its data-check attribute). A page with
a broken script must fail the same check, so the check can fail. Writes the
screenshot beside the page.
    check_viewer.py CLI MODEL OUTDIR
Exits 77 (skipped) when no chromium is installed."""
import html
import json
import pathlib
import re
import shutil
import struct
import subprocess
import sys
import tempfile

cli, model, outdir = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
browser = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
if browser is None:
    print("SKIP: no chromium installed (scripts/deps.sh installs Debian's 'chromium')")
    sys.exit(77)
outdir.mkdir(parents=True, exist_ok=True)

# A recording of the toy skeleton (tests/live/toy_stream.py), as a joint CSV file.
toy = pathlib.Path(__file__).parent.parent / "live" / "toy_stream.py"
csv = outdir / "toy.csv"
csv.write_text(subprocess.run([sys.executable, str(toy), "12", "--clean"], capture_output=True, text=True,
                              check=True).stdout)
page = outdir / "toy.html"
made = subprocess.run([cli, "view", str(csv), "--model", model, "--out", str(page), "--label", "raise_both",
                       "--title", "viewer test", "--settle", "0.5"], capture_output=True, text=True, timeout=120)
assert made.returncode == 0, made.stderr
text = page.read_text()

# Self-contained: nothing fetched from anywhere.
for needle in ("http://", "https://", "<link", " src=", "@import", "url("):
    assert needle not in text, f"the page refers to something outside itself: {needle!r}"


def load(path: pathlib.Path):
    """The page's DOM after its scripts ran, and chromium's log."""
    with tempfile.TemporaryDirectory() as profile:
        run = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", f"--user-data-dir={profile}",
                              "--enable-logging=stderr", "--v=0", "--window-size=1100,820", "--dump-dom",
                              path.resolve().as_uri()], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    root = re.search(r"<html[^>]*>", run.stdout)
    assert root, run.stdout[:500]
    attributes = dict(re.findall(r'(data-[a-z]+)="([^"]*)"', root.group(0)))
    return {k: html.unescape(v) for k, v in attributes.items()}, run.stderr


def problems(attributes, log):
    found = []
    if "data-errors" in attributes:
        found.append("script errors: " + attributes["data-errors"])
    found += [line for line in log.splitlines() if "Uncaught" in line or ":ERROR:CONSOLE" in line]
    if "data-check" not in attributes:
        found.append("the page never finished drawing (no data-check)")
        return found
    check = json.loads(attributes["data-check"])
    for canvas, least in (("skeleton", 300), ("overview", 2000), ("detail", 2000), ("margin", 100)):
        if check[canvas] < least:
            found.append(f"the {canvas} canvas drew {check[canvas]} pixels (at least {least} expected)")
    if check["rows"] != 4:
        found.append(f"{check['rows']} timeline rows (truth, settled, live, window expected)")
    if check["frames"] < 300 or check["joints"] != 5:
        found.append(f"{check['frames']} frames of {check['joints']} joints on the page")
    return found


attributes, log = load(page)
found = problems(attributes, log)
assert not found, "\n".join(found)
print("page drew:", attributes["data-check"])

# The same check on a page whose script is broken must fail.
broken = outdir / "broken.html"
broken.write_text(text.replace("JSON.parse(document", "JSON.parze(document", 1))
broken_found = problems(*load(broken))
assert broken_found, "a page with a broken script passed the check"
print("broken page caught:", broken_found[0])

# The screenshot: a PNG of the window's size.
shot = outdir / "toy.png"
with tempfile.TemporaryDirectory() as profile:
    subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", f"--user-data-dir={profile}",
                    "--hide-scrollbars", "--window-size=1100,820", f"--screenshot={shot}", page.resolve().as_uri()],
                   capture_output=True, text=True, timeout=120, check=True)
png = shot.read_bytes()
assert png[:8] == b"\x89PNG\r\n\x1a\n", "the screenshot is not a PNG"
width, height = struct.unpack(">II", png[16:24])
assert (width, height) == (1100, 820), (width, height)
print(f"screenshot {shot} ({len(png)} bytes, {width}x{height})")
