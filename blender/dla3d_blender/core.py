"""What the add-on needs from the `dla3d` command, without Blender: finding it, its option
description (`dla3d options`), the command line for a run, the run itself with its live stream
(docs/studio.md#the-stream), and the CSV it writes.

Pure Python and numpy, so that it works in any Blender's own Python and can be tested alone.
"""

import json
import os
import shutil
import signal
import struct
import subprocess
import tempfile
import threading
import time

import numpy as np

#: The `dla3d` versions (major, minor) whose options and stream this add-on was written against.
KNOWN_VERSIONS = {(0, 1)}

#: Options the add-on sets itself for every run, so its panel leaves them out: where the files
#: go and which, the live stream, and the progress bar (the stream carries the progress).
SET_BY_THE_ADDON = {"--output", "--formats", "--stream", "--quiet", "--preset"}

#: The type `dla3d options` gives a file option that reads a mesh: the add-on offers an object.
MESH_FILE = "MESH_FILE"


class Missing(Exception):
    """`dla3d` is not where the add-on looks, or cannot run: one line that says what to do."""


def find_dla3d(preferred=""):
    """The path of the `dla3d` executable: `preferred` (the add-on's preferences) when set,
    else the first on the PATH. Raises Missing, in one line, when neither runs."""
    if preferred:
        path = os.path.abspath(os.path.expanduser(preferred))
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        raise Missing(f"dla3d: {preferred} is not an executable file; set the path to dla3d in the add-on's preferences")
    found = shutil.which("dla3d")
    if not found:
        raise Missing("dla3d: not found on the PATH; install it (its README's setup) or set its path in the add-on's "
                      "preferences")
    return found


def version_of(path):
    """The version `dla3d --version` prints ("0.1.0"), and a one-line warning (or None) when
    this add-on does not know it."""
    try:
        done = subprocess.run([path, "--version"], capture_output=True, text=True, timeout=30)
    except OSError as error:
        raise Missing(f"dla3d: {path} does not run ({error.strerror})") from error
    words = done.stdout.split()
    if done.returncode != 0 or len(words) < 2 or words[0] != "dla3d":
        raise Missing(f"dla3d: {path} --version did not say it is dla3d")
    version = words[1]
    try:
        major_minor = tuple(int(part) for part in version.split(".")[:2])
    except ValueError:
        major_minor = None
    warning = None
    if major_minor not in KNOWN_VERSIONS:
        known = ", ".join(f"{a}.{b}" for a, b in sorted(KNOWN_VERSIONS))
        warning = f"dla3d {version} is newer or older than this add-on knows ({known}); its options are read from it"
    return version, warning


def read_description(path):
    """`dla3d options`: every model, its command words, options and presets."""
    done = subprocess.run([path, "options"], capture_output=True, text=True, timeout=60)
    if done.returncode != 0:
        raise Missing(f"dla3d: {path} options failed: {done.stderr.strip().splitlines()[-1:] or ['?']}")
    return json.loads(done.stdout)


def identifier(option_name):
    """The Python name of an option: `--rng-seed` -> `rng_seed`."""
    return option_name.lstrip("-").replace("-", "_")


def panel_options(model):
    """The options a panel shows for `model` (an entry of the description), in their order."""
    return [o for o in model["options"] if o["name"] not in SET_BY_THE_ADDON and
            (o["kind"] != "file" or o["type"] == MESH_FILE)]


def mesh_options(model):
    """The model's file options that read a mesh."""
    return [o for o in model["options"] if o["kind"] == "file" and o["type"] == MESH_FILE]


def main_mesh_option(model):
    """The mesh option the selected object goes to: the first of the group that holds most of
    them (`--stl` in "Mesh constraint", not a discharge's target electrode); None if none."""
    meshes = mesh_options(model)
    if not meshes:
        return None
    groups = [o["group"] for o in meshes]
    busiest = max(groups, key=groups.count)
    return next(o for o in meshes if o["group"] == busiest)


def number_default(option):
    """A number's default, or None when dla3d chooses it from other options (`--influence`)."""
    try:
        value = float(option["default"])
    except ValueError:
        return None
    return int(value) if option["kind"] == "integer" else value


def flag_default(option):
    """A flag's default: True, False, or None when it depends on other options (`--scene-mesh`)."""
    text = option["default"].strip().lower()
    if text in ("true", "1", "on"):
        return True
    if text in ("false", "0", "off"):
        return False
    return None if option["negation"] else False


def number_text(value):
    """A number as the command line takes it, shortest exact for an int, 7 digits for a float
    (Blender's properties hold single precision)."""
    if isinstance(value, int):
        return str(value)
    return f"{value:.7g}"


def option_words(option, value):
    """The command-line words that give `option` the panel's `value`, or [] when the value is
    the default (left to `dla3d`, so the record shows what was asked)."""
    name = option["name"]
    kind = option["kind"]
    if kind == "flag":
        default = flag_default(option)
        if isinstance(value, str):  # a flag whose default depends: "default", "on" or "off"
            return [] if value == "default" else [name] if value == "on" else [option["negation"][0]]
        if value == bool(default):
            return []
        return [name] if value else ([option["negation"][0]] if option["negation"] else [])
    if kind == "file":
        return [f"{name}={value}"] if value else []
    if kind in ("integer", "real") and not isinstance(value, str):  # a number with no default is text
        text = number_text(value)
        try:  # a single-precision default prints back as the default's own digits
            same = float(text) == float(option["default"])
        except ValueError:
            same = False
        return [] if same else [f"{name}={text}"]
    text = str(value).strip()
    if text == option["default"] or (not text and not option["default"]):
        return []
    if option["repeats"]:  # several values, split by ';' (`--seed-at 0,0,0; 10,0,0`)
        return [f"{name}={part.strip()}" for part in text.split(";") if part.strip()]
    return [f"{name}={text}"]


def command(dla3d, model, words, prefix, stream_fd):
    """The command line of a run: the model's command words, the option words, and the
    add-on's own: every file CSV and JSON at `prefix`, the stream to `stream_fd`, quiet."""
    return [dla3d, *model["command"], *words, "--output", prefix, "--formats", "csv,json",
            "--stream", f"/dev/fd/{stream_fd}", "--quiet"]


# The stream: frames of a header, then float32 x, y, z and int32 parents.
_HEADER = struct.Struct("<4sIQQQ")


class Run:
    """One `dla3d` run in its own process, its stream read by a thread as it grows.

    `take()` gives what arrived since the last call, without blocking; `stop()` ends the run as
    Ctrl-C does, keeping what grew; `finished` tells when the process has ended and the stream
    is read to its end."""

    def __init__(self, dla3d, model, words, folder=None):
        self.folder = folder or tempfile.mkdtemp(prefix="dla3d_")
        os.makedirs(self.folder, exist_ok=True)
        self.prefix = os.path.join(self.folder, "grown")
        read_end, write_end = os.pipe()
        self.argv = command(dla3d, model, words, self.prefix, write_end)
        self._lock = threading.Lock()
        self._positions = np.zeros((0, 3), np.float32)
        self._parents = np.zeros(0, np.int32)
        self._count = 0
        self.done = 0
        self.total = 0
        self.started = time.monotonic()
        # What dla3d says goes to a file, which no full pipe can stall.
        self.log = os.path.join(self.folder, "dla3d.log")
        try:
            with open(self.log, "wb") as log:
                self.process = subprocess.Popen(self.argv, pass_fds=(write_end,), stdin=subprocess.DEVNULL,
                                                stdout=log, stderr=log, start_new_session=True)
        except OSError:
            os.close(read_end)
            raise
        finally:
            os.close(write_end)
        self._reader = threading.Thread(target=self._read, args=(read_end,), daemon=True)
        self._reader.start()

    def _grow_to(self, size):
        if size <= len(self._parents):
            return
        capacity = max(size, 2 * len(self._parents), 1024)
        positions = np.zeros((capacity, 3), np.float32)
        parents = np.full(capacity, -1, np.int32)
        positions[:self._count] = self._positions[:self._count]
        parents[:self._count] = self._parents[:self._count]
        self._positions, self._parents = positions, parents

    def _read(self, fd):
        with os.fdopen(fd, "rb", buffering=1 << 16) as stream:
            while True:
                header = stream.read(_HEADER.size)
                if len(header) < _HEADER.size or header[:4] != b"DLAs":
                    return
                _, count, first, done, total = _HEADER.unpack(header)
                body = stream.read(16 * count)
                if len(body) < 16 * count:
                    return
                xyz = np.frombuffer(body, "<f4", 3 * count).reshape(count, 3)
                parents = np.frombuffer(body, "<i4", count, offset=12 * count)
                with self._lock:
                    self._grow_to(first + count)
                    self._positions[first:first + count] = xyz
                    self._parents[first:first + count] = parents
                    self._count = max(self._count, first + count)
                    self.done, self.total = done, total

    def snapshot(self, begin=0):
        """The particles that arrived so far from `begin` on: positions (float32, 3 a row) and
        parents."""
        with self._lock:
            return self._positions[begin:self._count].copy(), self._parents[begin:self._count].copy()

    def positions_of(self, indices):
        """The positions of the particles `indices` (all arrived)."""
        with self._lock:
            return self._positions[np.asarray(indices, np.int64)].copy()

    def arrived(self):
        """How many particles the stream has brought."""
        with self._lock:
            return self._count

    @property
    def finished(self):
        return self.process.poll() is not None and not self._reader.is_alive()

    def wait(self, timeout=None):
        """Waits for the process and the stream's end; the process's exit code."""
        code = self.process.wait(timeout)
        self._reader.join(timeout)
        return code

    def stop(self):
        """Ends the run as Ctrl-C does: `dla3d` keeps what grew and writes its files."""
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)

    def error(self):
        """The run's one-line error, once it failed; None while it runs or when it succeeded."""
        if self.process.poll() in (None, 0):
            return None
        with open(self.log, "r", encoding="utf-8", errors="replace") as log:
            lines = [line.strip() for line in log if line.strip()]
        return lines[-1] if lines else f"dla3d ended with code {self.process.returncode}"

    def status(self):
        """One line for Blender's status bar: the count, the rate, and the time left."""
        elapsed = max(time.monotonic() - self.started, 1e-9)
        count = self.arrived()
        text = f"dla3d: {count:,} particles, {count / elapsed:,.0f}/s"
        if self.total and self.done:
            left = elapsed * (self.total - self.done) / self.done
            text += f", {left:.0f} s left" if left < 120 else f", {left / 60:.1f} min left"
        return text


def read_csv(path):
    """The CSV dla3d writes (docs/formats.md): each column by its header name, as numpy
    arrays, integers where every value is one."""
    with open(path, "r", encoding="utf-8") as f:
        header = f.readline().strip().split(",")
    table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2) if os.path.getsize(path) > 0 else np.zeros((0, 0))
    columns = {}
    for k, name in enumerate(header):
        column = table[:, k] if table.size else np.zeros(0)
        if column.size and np.all(column == np.round(column)) and np.all(np.abs(column) < 2 ** 31):
            column = column.astype(np.int64)
        columns[name] = column
    return columns
