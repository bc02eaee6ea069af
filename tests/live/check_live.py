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
