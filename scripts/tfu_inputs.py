"""Input files of the Python scripts, checked as the C++ tools check theirs (cmodel/input_file.cpp,
docs/inputs-outputs.md "Input files"), with the same messages:

  * a regular file: a directory, named pipe (FIFO), device or socket is refused, and the file is
    opened with O_NONBLOCK, so a FIFO put in its place after the check cannot make the open wait;
  * at most a size bound, checked against the file's size before reading and while reading (files
    in /proc report size 0): /dev/zero behind a link is refused, never read until memory runs out;
  * a missing file, a permission problem, a name too long: one line, never a traceback.

Errors are InputError("LABEL: reason"), LABEL naming the input as the caller gives it.
"""
import errno
import os
import stat

# cmodel/input_file.hpp's kMaxTextInputBytes (testbench/test_io_files.cpp checks that they agree).
MAX_TEXT_INPUT_BYTES = 64 << 20


class InputError(Exception):
    pass


def _reason(e):
    return {
        errno.ENOENT: "no such file",
        errno.ENOTDIR: "no such file (a path component is not a directory)",
        errno.ENAMETOOLONG: "file name too long",
        errno.EACCES: "permission denied",
        errno.ELOOP: "too many levels of symbolic links",
    }.get(e.errno, e.strerror or str(e))


def _type_problem(mode):
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "is a directory, not a file"
    for test, kind in ((stat.S_ISFIFO, "a named pipe (FIFO)"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return f"is {kind}, not a regular file"
    return "is not a regular file"


def read_input_bytes(path, label, max_bytes=MAX_TEXT_INPUT_BYTES):
    """The whole file, checked as above."""
    if not path:
        raise InputError(f"{label}: empty file name")
    try:
        problem = _type_problem(os.stat(path).st_mode)
        if problem:
            raise InputError(f"{label}: {problem}")
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC | os.O_NOCTTY)
    except OSError as e:
        raise InputError(f"{label}: {_reason(e)}") from None
    with os.fdopen(fd, "rb") as f:
        st = os.fstat(f.fileno())
        problem = _type_problem(st.st_mode)
        if problem:
            raise InputError(f"{label}: {problem}")
        too_big = f"{label}: larger than the limit of {max_bytes} bytes for this input"
        if st.st_size > max_bytes:
            raise InputError(too_big)
        try:
            data = f.read(max_bytes + 1)
        except OSError as e:
            raise InputError(f"{label}: {_reason(e)}") from None
        if len(data) > max_bytes:
            raise InputError(too_big)
        return data


def read_input_text(path, label, max_bytes=MAX_TEXT_INPUT_BYTES):
    """The whole file as UTF-8 text (checked as above); a byte that is not UTF-8 is one line naming its offset."""
    data = read_input_bytes(path, label, max_bytes)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputError(f"{label}: not UTF-8 text (byte {e.start})") from None


def quoted(path):
    """A path for a message, as cmodel/error.hpp's quote_path: control characters as '?', at most 100
    characters (its head and tail around "..."), in single quotes."""
    s = "".join("?" if ord(c) < 0x20 or c == "\x7f" else c for c in str(path))
    if len(s) > 100:
        s = s[:30] + "..." + s[-67:]
    return f"'{s}'"


def error_line(program, message, limit=300):
    """The one error line a script prints: control characters as spaces, at most `limit` characters."""
    s = "".join(" " if ord(c) < 0x20 or c == "\x7f" else c for c in f"{program}: error: {message}")
    return s if len(s) <= limit else s[:limit - 3] + "..."
