"""The growth studio's web server (docs/studio.md): `dla3d studio` runs it.

It serves the page and, for each page open, a session on one WebSocket. A session's growth is a
run of the same dla3d, with `--stream` to a pipe: each frame of particles the run attaches goes
on to the page as it comes, and the files the page downloads are the run's own, the ones the
command it shows writes. Stop is the command line's Ctrl-C; Go on resumes DLA from its checkpoint
and grows any other model again from its seed, which ends as the uninterrupted run does.

Every request carries the token printed with the address, and names the studio by the Host it
listens on, from a page of its own Origin: no other web page, and no DNS rebinding, can drive it.
The client never names a path: uploads and runs go to a folder of the session's, under names
the server picks.
"""

import argparse
import asyncio
import hmac
import ipaddress
import json
import os
import re
import secrets
import shutil
import signal
import socket
import struct
import sys
import tempfile
import threading
import webbrowser

# Until serve() puts its own handlers in place, Ctrl-C ends the studio quietly, not with a
# traceback. dla3d hands the stop signals over blocked (cli/studio.cpp): one that came during
# Python's start-up lands here.
if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
    signal.signal(signal.SIGINT, signal.SIG_DFL)
signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})

try:
    from aiohttp import WSMsgType, web
except ImportError:
    print("dla3d: error: the studio needs Python's aiohttp: apt-get install python3-aiohttp", file=sys.stderr)
    sys.exit(1)

HERE = os.path.dirname(os.path.abspath(__file__))

UPLOAD_LIMIT = 64 << 20  # bytes: a mesh or a painted PLY
SESSION_LIMIT = 32  # pages open at once; each holds a folder
RUN_LIMIT = max(1, os.cpu_count() or 1)  # runs at once, over all sessions
MESSAGE_LIMIT = 64 << 10  # bytes of one message from the page
CONVERT_SECONDS = 120  # reading and repairing an upload
MESH_TYPES = ("stl", "obj", "ply", "off")
STREAM_HEADER = struct.Struct("<4sIQQQ")  # "DLAs", count, first, done, total
STREAM_FRAME_LIMIT = 1 << 24  # particles in one frame, what grew in 0.05 s: far above any model's

# Options the page may not give besides those that name files (kind "file": the server picks
# those): they belong to the server's own handling of the run.
SERVER_OPTIONS = {"--checkpoint-every", "--quiet", "--help", "--version"}

MASK_SIZE = 17  # sites a side of a painted Eden mask: each within 8 of the dropped one


def page_may_give(option):
    """Whether the page may give `option` (an entry of `dla3d options`): no file, no option of
    the server's."""
    return option["kind"] != "file" and option["name"] not in SERVER_OPTIONS


def names_file(option):
    """Whether `option`'s value may be a file's name: kind file, or text whose form has a FILE
    (Eden's --mask A|B|C|D|FILE). The page may give such text only its choices, as no client
    path may reach the file system."""
    return option["kind"] == "file" or (option["kind"] == "text" and "FILE" in option["type"].split("|"))


def painted_option(options, role):
    """The option among `options` that a painting gives, by its `paints` role (seeds,
    attractors, bare, mask); None if none."""
    return next((o for o in options if o.get("paints") == role), None)


def prefix_option(options):
    """The option that names the files' prefix: the file option of form PREFIX (-o)."""
    return next(o["name"] for o in options if o["kind"] == "file" and o["type"] == "PREFIX")


def main_mesh_option(options):
    """The name of the option an uploaded mesh goes to, among a model's `options`: the first
    mesh file of the group that holds most of them (grow's --stl, not a discharge's target
    electrode); None if the model reads no mesh."""
    meshes = [o for o in options if o["kind"] == "file" and o["type"] == "MESH_FILE"]
    if not meshes:
        return None
    groups = [o["group"] for o in meshes]
    busiest = max(groups, key=groups.count)
    return next(o["name"] for o in meshes if o["group"] == busiest)


def one_line(text):
    """The last error line of dla3d's stderr, without its prefix."""
    lines = [line for line in text.splitlines() if line.strip()]
    for line in reversed(lines):
        if line.startswith("dla3d: error: "):
            return line[len("dla3d: error: "):]
    return lines[-1] if lines else "dla3d failed with no message"


def refuse(status, text):
    """An HTTP error with a one-line plain text body."""
    return web.Response(status=status, text=text.replace("\n", " ") + "\n", content_type="text/plain")


class Studio:
    def __init__(self, dla3d, host, models):
        self.dla3d = dla3d
        self.host = host
        self.token = secrets.token_urlsafe(32)
        self.models = models  # `dla3d options`, parsed
        # Each option by its name and by its negations (--no-stop-at-strike), as a page may send either.
        self.options = {m["name"]: {name: o for o in m["options"] for name in [o["name"], *o["negation"]]}
                        for m in models["models"]}
        self.root = tempfile.mkdtemp(prefix="dla3d-studio-")
        self.sessions = {}
        self.runs = asyncio.Semaphore(RUN_LIMIT)
        self.hosts = set()  # Host headers that name this studio, once the port is known
        bust = os.path.join(HERE, "bust.off")
        self.bust = bust if os.path.isfile(bust) else None

    def listen_on(self, port):
        names = {self.host}
        if is_loopback(self.host):
            names |= {"127.0.0.1", "localhost", "[::1]"}
        self.hosts = {f"{name}:{port}" for name in names}
        if port == 80:
            self.hosts |= names

    # -- access ------------------------------------------------------------------------------

    @web.middleware
    async def guard(self, request, handler):
        host = request.headers.get("Host", "")
        if host not in self.hosts:
            return refuse(403, f"the Host '{host[:100]}' is not this studio's")
        origin = request.headers.get("Origin")
        if origin is not None and origin not in {"http://" + h for h in self.hosts}:
            return refuse(403, f"the Origin '{origin[:100]}' is not this studio's page")
        token = request.query.get("token", "") or request.headers.get("X-Studio-Token", "")
        if not hmac.compare_digest(token.encode(), self.token.encode()):
            return refuse(403, "a wrong or missing token: open the address dla3d studio printed")
        try:
            return await handler(request)
        except web.HTTPException as e:
            return refuse(e.status, e.reason if not e.text or e.text.startswith(str(e.status)) else e.text)

    def session_of(self, request):
        session = self.sessions.get(request.query.get("session", ""))
        if session is None:
            raise web.HTTPNotFound(reason="no such session: reload the page")
        return session

    # -- the page ----------------------------------------------------------------------------

    async def page(self, request):
        with open(os.path.join(HERE, "index.html"), encoding="utf-8") as f:
            html = f.read().replace("{{token}}", self.token)
        return web.Response(text=html, content_type="text/html", headers={"Cache-Control": "no-store"})

    async def script(self, request):
        return web.FileResponse(os.path.join(HERE, "studio.js"), headers={"Content-Type": "text/javascript"})

    async def model_list(self, request):
        return web.json_response({"models": self.models["models"], "version": self.models["version"],
                                  "server_options": sorted(SERVER_OPTIONS), "bust": self.bust is not None,
                                  "upload_limit": UPLOAD_LIMIT, "mesh_types": MESH_TYPES})

    # -- meshes ------------------------------------------------------------------------------

    async def read_body(self, request):
        if request.content_length is not None and request.content_length > UPLOAD_LIMIT:
            raise web.HTTPRequestEntityTooLarge(max_size=UPLOAD_LIMIT, actual_size=request.content_length,
                                                text=f"the upload is over {UPLOAD_LIMIT >> 20} MiB")
        body = bytearray()
        async for chunk in request.content.iter_chunked(1 << 16):
            body += chunk
            if len(body) > UPLOAD_LIMIT:
                raise web.HTTPRequestEntityTooLarge(max_size=UPLOAD_LIMIT, actual_size=len(body),
                                                    text=f"the upload is over {UPLOAD_LIMIT >> 20} MiB")
        if not body:
            raise web.HTTPBadRequest(text="the upload is empty")
        return bytes(body)

    async def convert(self, session, source):
        """The library's reading and repair of `source` (dla3d convert), into mesh.stl; the
        page is sent that, to draw and paint."""
        if session.run is not None:
            raise web.HTTPConflict(text="busy: a run is under way; stop it first")
        target = os.path.join(session.folder, "mesh.stl")
        for name in ("mesh.stl", "painted.ply"):
            if os.path.exists(os.path.join(session.folder, name)):
                os.remove(os.path.join(session.folder, name))
        process = await asyncio.create_subprocess_exec(self.dla3d, "convert", source, target,
                                                       stdout=asyncio.subprocess.DEVNULL,
                                                       stderr=asyncio.subprocess.PIPE)
        try:
            _, err = await asyncio.wait_for(process.communicate(), CONVERT_SECONDS)
        except asyncio.TimeoutError:
            process.kill()
            await process.wait()
            raise web.HTTPBadRequest(text=f"the mesh took over {CONVERT_SECONDS} s to read")
        if process.returncode != 0:
            raise web.HTTPBadRequest(text=one_line(err.decode("utf-8", "replace")).replace(source, "the upload"))
        session.mesh = "mesh.stl"
        return web.FileResponse(target, headers={"Content-Type": "model/stl"})

    async def upload_mesh(self, request):
        session = self.session_of(request)
        kind = request.query.get("type", "").lower()
        if kind not in MESH_TYPES:
            raise web.HTTPBadRequest(text="the mesh's type must be one of " + ", ".join(MESH_TYPES))
        body = await self.read_body(request)
        source = os.path.join(session.folder, "upload." + kind)
        with open(source, "wb") as f:
            f.write(body)
        try:
            return await self.convert(session, source)
        finally:
            os.remove(source)

    async def bust_mesh(self, request):
        session = self.session_of(request)
        if self.bust is None:
            raise web.HTTPNotFound(text="the bust is not installed (CGAL's data set, libcgal-demo)")
        return await self.convert(session, self.bust)

    async def paint(self, request):
        """The mesh with its paint as vertex colours, a PLY the page writes: the run's --stl."""
        session = self.session_of(request)
        if session.mesh is None:
            raise web.HTTPConflict(text="load a mesh before painting it")
        body = await self.read_body(request)
        if not body.startswith(b"ply\n"):
            raise web.HTTPBadRequest(text="the painted mesh is not a PLY")
        with open(os.path.join(session.folder, "painted.ply"), "wb") as f:
            f.write(body)
        return web.json_response({"painted": len(body)})

    async def download(self, request):
        session = self.session_of(request)
        name = request.query.get("name", "")
        # Only a file of the session's folder, by its plain name: never a path.
        if not re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,200}", name) or name not in os.listdir(session.folder):
            raise web.HTTPNotFound(text=f"no file '{name[:100]}' in this session")
        return web.FileResponse(os.path.join(session.folder, name),
                                headers={"Content-Disposition": f'attachment; filename="{name}"'})

    # -- sessions and runs -------------------------------------------------------------------

    async def socket(self, request):
        if len(self.sessions) >= SESSION_LIMIT:
            return refuse(503, f"busy: {SESSION_LIMIT} pages are open; close one")
        # No WebSocket heartbeat: its ping waits behind the stream's frames, and a page that
        # draws them slowly (a big run, a browser without a GPU) answers too late and is cut
        # off. The kernel's keepalive probes, answered by the other end's kernel, find a client
        # that is gone instead.
        ws = web.WebSocketResponse(max_msg_size=MESSAGE_LIMIT)
        await ws.prepare(request)
        keep_alive(request.transport)
        session = Session(self, ws)
        self.sessions[session.id] = session
        try:
            await session.send({"type": "hello", "session": session.id, "runs": RUN_LIMIT})
            async for message in ws:
                if message.type != WSMsgType.TEXT:
                    await session.send({"type": "error", "line": "messages are JSON text"})
                    continue
                try:
                    asked = json.loads(message.data)
                    if not isinstance(asked, dict):
                        raise ValueError("not an object")
                except ValueError as e:
                    await session.send({"type": "error", "line": f"a message that is not a JSON object: {e}"})
                    continue
                await session.handle(asked)
        finally:
            del self.sessions[session.id]
            await session.close()
        return ws

    def command_of(self, model, options, mesh, files=()):
        """The dla3d command (without the program) for a page's choice, with `files`, the
        [name, file] options the server wrote for it, or ValueError's line."""
        if not isinstance(model, str) or model not in self.options:
            raise ValueError(f"no model '{str(model)[:50]}': one of " + ", ".join(self.options))
        known = self.options[model]
        if not isinstance(options, list) or len(options) > 200:
            raise ValueError("options are a list of [name, value] pairs, at most 200")
        words = [] if model == "grow" else [model]
        seen = set()
        for pair in options:
            if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(p, str) for p in pair)):
                raise ValueError("each option is a [name, value] pair of strings")
            name, value = pair
            option = known.get(name)
            if option is None:
                raise ValueError(f"{model} has no option '{name[:50]}'")
            if not page_may_give(option):
                raise ValueError(f"{name} names a file, or is the studio's: the studio chooses those")
            if names_file(option) and value not in option.get("choices", []):
                raise ValueError(f"{name} is one of " + ", ".join(option.get("choices", [])) + " here: no file names")
            if name in seen and not option["repeats"]:
                raise ValueError(f"{name} is given twice")
            seen.add(name)
            if len(value) > 1000 or "\0" in value:
                raise ValueError(f"{name}'s value is over 1000 characters")
            if option["flag"]:
                if value not in ("", "true", "false"):
                    raise ValueError(f"{name} is a switch: its value is true or false")
                if value != "false":
                    words.append(name)
            else:
                words += [name, value]
        listed = next(m["options"] for m in self.models["models"] if m["name"] == model)
        if mesh is not None:
            main = main_mesh_option(listed)
            if main is None:
                raise ValueError(f"{model} grows in no mesh")
            words += [main, mesh]
        for name, file in files:
            if name not in known or name in seen:
                raise ValueError(f"{name} is the studio's to write here, and {model} takes it from the page once")
            words += [name, file]
        return words + [prefix_option(listed), "run"]


def keep_alive(transport):
    """TCP keepalive on a connection: one silent for 30 s is probed every 10 s, and closed
    after 3 probes go unanswered."""
    sock = transport.get_extra_info("socket") if transport is not None else None
    if sock is None:
        return
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_KEEPALIVE, 1)
    for option, value in (("TCP_KEEPIDLE", 30), ("TCP_KEEPINTVL", 10), ("TCP_KEEPCNT", 3)):
        if hasattr(socket, option):
            sock.setsockopt(socket.IPPROTO_TCP, getattr(socket, option), value)


def mask_text(rows):
    """A painted Eden mask, rows of '.', 'x' (a site it counts) and one 'o' (the dropped site),
    top row first, as the text of a --mask file (docs/eden.md), or ValueError's line."""
    if not (isinstance(rows, list) and 1 <= len(rows) <= MASK_SIZE and all(isinstance(r, str) for r in rows)):
        raise ValueError(f"a mask is a list of 1 to {MASK_SIZE} rows of text")
    if any(len(r) > MASK_SIZE or not re.fullmatch(r"[.xo]+", r) for r in rows):
        raise ValueError(f"a mask's rows are 1 to {MASK_SIZE} of '.', 'x' and 'o'")
    text = "".join(rows)
    if text.count("o") != 1 or "x" not in text:
        raise ValueError("a mask has one 'o', the dropped site, and at least one 'x'")
    return "; painted in dla3d studio\n" + "\n".join(rows) + "\n"


def is_loopback(host):
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return host == "localhost"


class Session:
    def __init__(self, studio, ws):
        self.studio = studio
        self.ws = ws
        self.id = secrets.token_urlsafe(12)
        self.folder = os.path.join(studio.root, self.id)
        os.mkdir(self.folder)
        self.mesh = None  # "mesh.stl" once one is loaded
        self.run = None  # the task of the run under way
        self.process = None
        self.command = None  # the last run's words, for Go on
        self.stopped = False

    async def send(self, message):
        if not self.ws.closed:
            await self.ws.send_str(json.dumps(message))

    async def handle(self, asked):
        kind = asked.get("type")
        if kind == "grow":
            if self.run is not None:
                return await self.send({"type": "busy", "line": "busy: this page's run is under way"})
            mesh = None
            if asked.get("mesh") in ("mesh", "painted"):
                if self.mesh is None:
                    return await self.send({"type": "error", "line": "no mesh is loaded"})
                painted = asked["mesh"] == "painted" and os.path.exists(os.path.join(self.folder, "painted.ply"))
                mesh = "painted.ply" if painted else "mesh.stl"
            try:
                files = []
                if asked.get("mask") is not None:
                    model = asked.get("model")
                    listed = self.studio.options.get(model, {}) if isinstance(model, str) else {}
                    option = painted_option(listed.values(), "mask")
                    if option is None:
                        raise ValueError(f"{str(asked.get('model'))[:50]} reads no painted mask")
                    mask = mask_text(asked["mask"])
                    with open(os.path.join(self.folder, "mask.txt"), "w") as f:
                        f.write(mask)
                    files.append([option["name"], "mask.txt"])
                words = self.studio.command_of(asked.get("model"), asked.get("options", []), mesh, files)
            except ValueError as e:
                return await self.send({"type": "error", "line": str(e)})
            self.command = words
            for name in os.listdir(self.folder):
                if name.startswith("run"):
                    os.remove(os.path.join(self.folder, name))
            # A model that goes on from a checkpoint (DLA) writes one as it grows, for Go on.
            resumes = "--checkpoint" in self.studio.options[asked["model"]]
            checkpoint = ["--checkpoint", "run.ck"] if resumes else []
            self.start(words, words + checkpoint, resumed=False)
        elif kind == "goon":
            if self.run is not None:
                return await self.send({"type": "busy", "line": "busy: this page's run is under way"})
            if self.command is None:
                return await self.send({"type": "error", "line": "there is no run to go on with"})
            if os.path.exists(os.path.join(self.folder, "run.ck")):
                self.start(self.command, ["--resume", "run.ck"], resumed=True)
            else:
                self.start(self.command, self.command, resumed=True)
        elif kind == "stop":
            if self.process is not None and self.process.returncode is None:
                self.stopped = True
                self.process.send_signal(signal.SIGINT)
        else:
            await self.send({"type": "error", "line": f"no request '{str(kind)[:50]}': grow, stop or goon"})

    def start(self, shown, words, resumed):
        self.stopped = False
        self.run = asyncio.ensure_future(self.grow(shown, words, resumed))

    async def grow(self, shown, words, resumed):
        studio = self.studio
        if studio.runs.locked():
            await self.send({"type": "busy", "line": f"busy: {RUN_LIMIT} runs are under way; try again soon"})
            self.run = None
            return
        async with studio.runs:
            read_end, write_end = os.pipe()
            try:
                self.process = await asyncio.create_subprocess_exec(
                    studio.dla3d, *words, "--stream", f"/dev/fd/{write_end}", cwd=self.folder,
                    stdin=asyncio.subprocess.DEVNULL, stdout=asyncio.subprocess.DEVNULL,
                    stderr=asyncio.subprocess.PIPE, pass_fds=(write_end,), start_new_session=True)
            finally:
                os.close(write_end)
            await self.send({"type": "started", "command": ["dla3d", *shown], "resumed": resumed})
            reader = asyncio.StreamReader(limit=1 << 20)
            transport, _ = await asyncio.get_running_loop().connect_read_pipe(
                lambda: asyncio.StreamReaderProtocol(reader), os.fdopen(read_end, "rb", buffering=0))
            errors = asyncio.ensure_future(self.process.stderr.read())
            try:
                await self.relay(reader)
            finally:
                transport.close()
            err = (await errors).decode("utf-8", "replace")
            code = await self.process.wait()
            self.process = None
        files = sorted(n for n in os.listdir(self.folder) if n.startswith("run") and not n.endswith((".ck", ".tmp")))
        if code == 0 or (self.stopped and code in (128 + signal.SIGINT, 0)):
            await self.send({"type": "done", "stopped": code != 0, "files": files, "command": ["dla3d", *shown],
                             "log": [l for l in err.splitlines() if l.strip()][-5:]})
        else:
            await self.send({"type": "error", "line": one_line(err), "files": files})
        self.run = None

    async def relay(self, reader):
        """The run's frames, each on to the page as one binary message."""
        while True:
            try:
                head = await reader.readexactly(STREAM_HEADER.size)
            except asyncio.IncompleteReadError:
                return
            magic, count, _, _, _ = STREAM_HEADER.unpack(head)
            if magic != b"DLAs" or count > STREAM_FRAME_LIMIT:
                return
            try:
                body = await reader.readexactly(16 * count)
            except asyncio.IncompleteReadError:
                return
            if not self.ws.closed:
                await self.ws.send_bytes(head + body)

    async def close(self):
        """The page went away: its run stops (Ctrl-C, then at once), and its folder goes."""
        process = self.process
        if process is not None and process.returncode is None:
            process.send_signal(signal.SIGINT)
            try:
                await asyncio.wait_for(process.wait(), 5)
            except asyncio.TimeoutError:
                process.kill()
        if self.run is not None:
            try:
                await asyncio.wait_for(self.run, 10)
            except (asyncio.TimeoutError, Exception):
                pass
        shutil.rmtree(self.folder, ignore_errors=True)


def resolves(host, seconds=10):
    """Whether `host` names an address. The resolver is asked on a thread of its own, so that
    one that never answers (a machine without a network) holds the studio `seconds` at most."""
    found = []

    def ask():
        try:
            found.append(bool(socket.getaddrinfo(host, None, type=socket.SOCK_STREAM)))
        except (OSError, UnicodeError):
            found.append(False)

    thread = threading.Thread(target=ask, daemon=True)
    thread.start()
    thread.join(seconds)
    return bool(found and found[0])


async def serve(arguments):
    # Handlers first: a Ctrl-C at any point from here on, even while the browser opens, stops
    # cleanly; one before the studio listens ends it as the signal does the command line's runs.
    stop = asyncio.Event()
    stopped_by = []
    loop = asyncio.get_running_loop()
    for number in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(number, lambda number=number: (stopped_by.append(number), stop.set()))
    if not resolves(arguments.host):
        if stop.is_set():
            return 128 + stopped_by[0]
        print(f"dla3d: error: cannot listen on {arguments.host}: no address has that name", file=sys.stderr)
        return 1
    options = await asyncio.create_subprocess_exec(arguments.dla3d, "options", stdout=asyncio.subprocess.PIPE)
    out, _ = await options.communicate()
    if stop.is_set():
        return 128 + stopped_by[0]
    if options.returncode != 0:
        print(f"dla3d: error: `{arguments.dla3d} options` failed with exit {options.returncode}", file=sys.stderr)
        return 1
    studio = Studio(arguments.dla3d, arguments.host, json.loads(out))
    app = web.Application(middlewares=[studio.guard], client_max_size=UPLOAD_LIMIT + 4096)
    app.add_routes([web.get("/", studio.page), web.get("/studio.js", studio.script),
                    web.get("/api/models", studio.model_list), web.get("/api/session", studio.socket),
                    web.post("/api/mesh", studio.upload_mesh), web.post("/api/bust", studio.bust_mesh),
                    web.post("/api/paint", studio.paint), web.get("/api/file", studio.download)])
    runner = web.AppRunner(app, access_log=None, handle_signals=False)
    await runner.setup()
    site = web.TCPSite(runner, arguments.host, arguments.port, reuse_address=True)
    try:
        await site.start()
    except OSError as e:
        shutil.rmtree(studio.root, ignore_errors=True)
        print(f"dla3d: error: cannot listen on {arguments.host}:{arguments.port}: {e.strerror}", file=sys.stderr)
        return 1
    port = site._server.sockets[0].getsockname()[1]
    studio.listen_on(port)
    shown_host = f"[{arguments.host}]" if ":" in arguments.host else arguments.host
    address = f"http://{shown_host}:{port}/?token={studio.token}"
    print(f"dla3d studio: {address}", flush=True)
    if not is_loopback(arguments.host):
        print("dla3d studio: listening beyond this machine: anyone with the address can grow on it", flush=True)
    if arguments.open:
        webbrowser.open(address)
    await stop.wait()
    # A second stop signal during the shutdown (a shell's Ctrl-C reaches the whole process group,
    # `timeout` forwards its own as well) waits, blocked, and dies with the process: leaving,
    # asyncio would hand SIGINT back to Python's KeyboardInterrupt, and exit 130.
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
    for session in list(studio.sessions.values()):
        await session.ws.close()
    await runner.cleanup()
    shutil.rmtree(studio.root, ignore_errors=True)
    return 0


def main():
    parser = argparse.ArgumentParser(prog="dla3d studio")
    parser.add_argument("--dla3d", required=True)
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=8765)
    parser.add_argument("--open", action="store_true")
    sys.exit(asyncio.run(serve(parser.parse_args())))


if __name__ == "__main__":
    main()
