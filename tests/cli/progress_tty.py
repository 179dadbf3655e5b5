"""ctest cli.progress_tty: the progress bar shows on a terminal, never elsewhere.

    /usr/bin/python3 tests/cli/progress_tty.py EMBER_BINARY WORK_DIR

EMBER_PROGRESS_DELAY_MS=0 stands in for a run longer than the 2 s delay.
Standard library only (pty), so it needs no Python module.
"""
import os
import pty
import subprocess
import sys

ember, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
subprocess.run([ember, "demo", "-o", work], check=True, stdout=subprocess.DEVNULL)
torus, sphere = os.path.join(work, "torus.obj"), os.path.join(work, "sphere.obj")
env = dict(os.environ, EMBER_PROGRESS_DELAY_MS="0")


def run_on_tty(extra):
    """Runs ember with stderr on a pseudo-terminal; returns what it wrote there."""
    main, sub = pty.openpty()
    p = subprocess.Popen([ember, "union", torus, sphere, "-o", os.path.join(work, "u.obj")] + extra,
                         stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=sub, env=env)
    os.close(sub)
    out = b""
    while True:
        try:
            chunk = os.read(main, 4096)
        except OSError:  # EIO: the child closed its end
            break
        if not chunk:
            break
        out += chunk
    os.close(main)
    if p.wait() != 0:
        sys.exit("ember failed on a terminal: %r" % out)
    return out.decode(errors="replace")


failures = []
tty = run_on_tty([])
if "ember: " not in tty or "[" not in tty or "%" not in tty:
    failures.append("no progress bar on a terminal: %r" % tty)
if "done" not in tty and "export" not in tty and "solve" not in tty:
    failures.append("no phase name in the progress line: %r" % tty)
if run_on_tty(["--quiet"]).strip():
    failures.append("--quiet still drew progress on a terminal")
piped = subprocess.run([ember, "union", torus, sphere, "-o", os.path.join(work, "p.obj")],
                       stderr=subprocess.PIPE, env=env, check=True).stderr
if piped:
    failures.append("progress written to a pipe: %r" % piped)
if failures:
    sys.exit("\n".join(failures))
print("progress_tty: all passed")
