"""`annotate --live` from a pipe and from a UDP socket on the loopback: JSON
lines come out as frames go in, malformed lines are skipped and counted, and
each run ends within a bounded time.
    check_live.py CLI MODEL"""
import json
import pathlib
import socket
import subprocess
import sys
import time

cli, model = sys.argv[1], sys.argv[2]
generator = [sys.executable, str(pathlib.Path(__file__).with_name("toy_stream.py")), "6"]
stream = subprocess.run(generator, capture_output=True, text=True, check=True).stdout.splitlines()


def check(stdout: str, stderr: str, what: str) -> None:
    lines = [json.loads(line) for line in stdout.splitlines()]  # every line is JSON
    settled = [x for x in lines if "settled" in x]
    started = [x for x in lines if x.get("event") == "started"]
    ended = [x for x in lines if x.get("event") == "ended"]
    assert settled, f"{what}: no settled label came out"
    assert started and len(started) == len(ended), f"{what}: events not in pairs: {started} {ended}"
    assert "2 malformed lines skipped" in stderr, f"{what}: {stderr}"
    # the frame without a body is no malformed line: a lost frame, which the annotator rejects
    assert "1 frames rejected by the annotator" in stderr, f"{what}: {stderr}"
    print(f"{what}: {len(settled)} label changes, {len(started)} actions, malformed lines skipped and counted")


# A pipe: the generator writes, annotate reads standard input until it closes.
producer = subprocess.Popen(generator, stdout=subprocess.PIPE)
done = subprocess.run([cli, "annotate", "--model", model, "--live", "--settle", "0.5"], stdin=producer.stdout,
                      capture_output=True, text=True, timeout=60)
producer.wait(timeout=60)
assert done.returncode == 0, done.stderr
check(done.stdout, done.stderr, "pipe")

# UDP on 127.0.0.1: a header datagram, then frames, a few per datagram; idle for 1.5 s ends the stream.
with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
    probe.bind(("127.0.0.1", 0))
    port = probe.getsockname()[1]
annotator = subprocess.Popen([cli, "annotate", "--model", model, "--live", "--udp", str(port), "--idle-timeout", "1.5",
                              "--settle", "0.5"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
assert "listening" in annotator.stderr.readline()
with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sender:
    sender.sendto((stream[0] + "\n").encode(), ("127.0.0.1", port))
    for i in range(1, len(stream), 3):
        sender.sendto(("\n".join(stream[i:i + 3]) + "\n").encode(), ("127.0.0.1", port))
        time.sleep(0.002)
stdout, stderr = annotator.communicate(timeout=60)
assert annotator.returncode == 0, stderr
check(stdout, stderr, "udp")

# The same recording as a file: annotate on the file and annotate --live from a pipe give
# the same action events, and every settled label the live run printed is the file's
# settled label at that time.
import tempfile  # noqa: E402

clean = subprocess.run([sys.executable, str(pathlib.Path(__file__).with_name("toy_stream.py")), "6", "--clean"],
                       capture_output=True, text=True, check=True).stdout
with tempfile.TemporaryDirectory() as tmp:
    recording = pathlib.Path(tmp) / "recording.csv"
    recording.write_text(clean)
    options = ["--model", model, "--settle", "0.5"]
    on_file = subprocess.run([cli, "annotate", *options, str(recording), "--events"], capture_output=True, text=True,
                             timeout=60, check=True).stdout
    spans = json.loads(subprocess.run([cli, "annotate", *options, str(recording), "--json"], capture_output=True,
                                      text=True, timeout=60, check=True).stdout)["segments"]
    piped = subprocess.run([cli, "annotate", *options, "--live"], input=clean, capture_output=True, text=True,
                           timeout=60, check=True).stdout
file_events = [json.loads(line) for line in on_file.splitlines()]
live_lines = [json.loads(line) for line in piped.splitlines()]
live_events = [x for x in live_lines if "event" in x]
assert file_events and live_events == file_events, f"events differ:\n{file_events}\n{live_events}"
for x in (x for x in live_lines if "settled" in x):
    covering = [s for s in spans if s["start"] <= x["time"] + 1e-6]  # times print rounded to 0.1 ms
    assert covering and covering[-1]["label"] == x["settled"], f"live said {x}, the file's timeline {spans}"
print(f"file and pipe: the same {len(file_events)} events and settled labels")

# With early settling a frame may settle a run of characters at once: the live run still
# prints every change of the settled label, where the file's timeline has it.
with tempfile.TemporaryDirectory() as tmp:
    recording = pathlib.Path(tmp) / "recording.csv"
    recording.write_text(clean)
    options = ["--model", model, "--settle", "2", "--settle-stable", "0.5"]
    spans = json.loads(subprocess.run([cli, "annotate", *options, str(recording), "--json"], capture_output=True,
                                      text=True, timeout=60, check=True).stdout)["segments"]
    piped = subprocess.run([cli, "annotate", *options, "--live"], input=clean, capture_output=True, text=True,
                           timeout=60, check=True).stdout
changes = [json.loads(line) for line in piped.splitlines() if "settled" in line]
runs = [s for i, s in enumerate(spans) if i == 0 or s["label"] != spans[i - 1]["label"]]
assert [x["settled"] for x in changes] == [s["label"] for s in runs], f"live {changes}, the file's {runs}"
assert all(abs(x["time"] - s["start"]) <= 1e-3 for x, s in zip(changes, runs)), f"live {changes}, file {runs}"
print(f"early settling: the same {len(changes)} settled label changes live and from the file")
