"""Shared pieces of scripts/capture-openarena and scripts/mesa-frame (docs/capture.md): one-line
errors, the Debian packages they need, a private Xvfb display, a child process with a deadline,
and the SwapBuffers-delimited frames of an apitrace trace.

Imported by those scripts only (Debian's /usr/bin/python3)."""
import os
import re
import select
import signal
import subprocess
import sys
import tempfile

# Software GL for every process these scripts start: Mesa through GLX on the Xvfb display.
SOFTWARE_GL = {"LIBGL_ALWAYS_SOFTWARE": "1"}


class InputError(Exception):
    """Bad input or a failed tool: one line, exit 2."""


def fail(prog, message):
    """Prints `prog: error: message` as one line of at most 300 characters and exits 2."""
    line = f"{prog}: error: {' '.join(str(message).split())}"
    if len(line) > 300:
        line = line[:297] + "..."
    print(line, file=sys.stderr)
    sys.exit(2)


def package_versions(names):
    """{package: version or None} from dpkg-query (None: not installed)."""
    out = {}
    for name in names:
        p = subprocess.run(["dpkg-query", "-W", "-f=${Status}\t${Version}", name], capture_output=True, text=True)
        status, _, version = p.stdout.partition("\t")
        out[name] = version if p.returncode == 0 and status.endswith("install ok installed") else None
    return out


def ensure_packages(names, prog):
    """Installs the Debian packages of `names` that are missing (apt-get as root, else through sudo);
    raises InputError naming them when that is not possible or fails."""
    missing = [n for n, v in package_versions(names).items() if v is None]
    if not missing:
        return
    if os.geteuid() == 0:
        sudo = []
    elif subprocess.run(["sh", "-c", "command -v sudo"], capture_output=True).returncode == 0:
        sudo = ["sudo"]
    else:
        raise InputError(f"need root or sudo to install the missing packages: {' '.join(missing)}")
    print(f"{prog}: installing {' '.join(missing)}", file=sys.stderr)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    for cmd in (["apt-get", "update", "-qq"], ["apt-get", "install", "-y", "-qq", "--no-install-recommends"] + missing):
        p = subprocess.run(sudo + cmd, capture_output=True, text=True, env=env)
        if p.returncode != 0:
            last = (p.stderr.strip().splitlines() or ["(no message)"])[-1]
            raise InputError(f"installing {' '.join(missing)} failed: {last}")


class Xvfb:
    """A private X display (Xvfb picks a free display number itself, -displayfd), stopped on exit."""

    def __init__(self, width, height):
        self.width, self.height = width, height
        self.proc = None
        self.display = None

    def __enter__(self):
        rfd, wfd = os.pipe()
        self.proc = subprocess.Popen(["Xvfb", "-displayfd", str(wfd), "-screen", "0", f"{self.width}x{self.height}x24",
                                      "-nolisten", "tcp", "-noreset"], pass_fds=(wfd,), stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL, start_new_session=True)
        os.close(wfd)
        text = b""
        while not text.endswith(b"\n"):
            ready, _, _ = select.select([rfd], [], [], 20)
            chunk = os.read(rfd, 64) if ready else b""
            if not chunk:
                break
            text += chunk
        os.close(rfd)
        if not re.fullmatch(rb"\d+\n", text):
            self.__exit__(None, None, None)
            raise InputError("Xvfb did not start (no display number within 20 s)")
        self.display = ":" + text.decode().strip()
        return self

    def __exit__(self, *exc):
        if self.proc and self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        return False


def run_with_deadline(args, env, timeout, log_path, what):
    """Runs `args` in its own process group with stdout and stderr to `log_path`; on timeout kills that
    group (only it) and raises InputError. Returns the exit status."""
    with open(log_path, "wb") as log:
        proc = subprocess.Popen(args, env=env, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                start_new_session=True)
        try:
            return proc.wait(timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            raise InputError(f"{what} did not finish within {timeout} s (killed; log lines: {last_lines(log_path)})")


def last_lines(path, n=2):
    try:
        with open(path, errors="replace") as f:
            lines = [l.strip() for l in f if l.strip() and not l.startswith(("ALSA lib", "GL_EXTENSIONS"))]
    except OSError:
        return "none"
    return " | ".join(lines[-n:]) if lines else "none"


def trace_frames(trace):
    """The frames of an apitrace trace as apitrace counts them (`apitrace dump`, `glretrace -S frame`):
    frame k is the calls after the k-th SwapBuffers up to and including the (k+1)-th. Returns
    (the call number of every frame's SwapBuffers in order, the call numbers of every glReadPixels)."""
    p = subprocess.run(["apitrace", "dump", "--color=never", "--arg-names=no", "--grep=SwapBuffers|CGLFlushDrawable|glReadPixels", trace], capture_output=True, text=True,
                       errors="replace")
    if p.returncode != 0:
        raise InputError(f"apitrace dump {trace} failed: {last_err(p.stderr)}")
    swaps, reads = [], []
    for line in p.stdout.splitlines():
        m = re.match(r"(\d+) (\w+)\(", line)
        if not m:
            continue
        if m.group(2) in ("glXSwapBuffers", "eglSwapBuffers", "wglSwapBuffers", "CGLFlushDrawable"):
            swaps.append(int(m.group(1)))
        elif m.group(2) == "glReadPixels":
            reads.append(int(m.group(1)))
    return swaps, reads


def last_err(text):
    lines = [l.strip() for l in text.splitlines() if l.strip()]
    return lines[-1] if lines else "(no message)"


def private_tempdir(prefix, parent=None):
    """mkdtemp (mode 0700, an unpredictable name) under `parent`, else $TMPDIR or /tmp."""
    return tempfile.mkdtemp(prefix=prefix, dir=parent)
