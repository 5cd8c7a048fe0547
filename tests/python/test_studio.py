"""The growth studio (dla3d studio, docs/studio.md), started as a user starts it, on loopback:
its access checks, uploads, option checks, runs streamed over the WebSocket, a fuzz of bad
requests, twenty clients at once, and, in Debian's Chromium, the page a user drives.

Chromium and Playwright are heavy clients: without them the page's test is skipped by name. The
rest needs only the studio's own dependencies (python3-aiohttp), which the setup installs."""

import asyncio
import http.client
import json
import os
import random
import re
import select
import shutil
import signal
import struct
import subprocess
import time
import urllib.parse

import pytest

import aiohttp  # python3-aiohttp, in the README's setup

DLA3D = os.environ.get("DLA3D", "dla3d")
CLIENTS = os.environ.get("TEST_CLIENTS_DIR", "")
FRAME = struct.Struct("<4sIQQQ")


def rss_kib(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise AssertionError("no VmRSS")


def children(pid):
    """The processes the studio runs (its dla3d runs), by /proc."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
                if int(fields[1]) == pid:
                    found.append(int(entry))
            except OSError:
                pass
    return found


class Studio:
    def __init__(self, *options):
        env = dict(os.environ, BROWSER="true")  # --open must open nothing here
        self.process = subprocess.Popen([DLA3D, "studio", "--port", "0", *options], stdout=subprocess.PIPE,
                                        stderr=subprocess.PIPE, env=env, text=True)
        # The address line is the event: the server listens once it is printed.
        ready, _, _ = select.select([self.process.stdout], [], [], 60)
        assert ready, "the studio printed no address within a minute"
        line = self.process.stdout.readline()
        assert line.startswith("dla3d studio: http://"), line + self.process.stderr.read()
        self.address = line.split(": ", 1)[1].strip()
        url = urllib.parse.urlparse(self.address)
        self.netloc = url.netloc
        self.base = f"http://{url.netloc}"
        self.token = urllib.parse.parse_qs(url.query)["token"][0]
        self.pid = self.server_pid()

    def server_pid(self):
        # dla3d execs Python in its own place: the same process.
        return self.process.pid

    def request(self, method, path, body=None, headers=None, token=True, query=None):
        query = dict(query or {})
        if token:
            query.setdefault("token", self.token)
        target = path + ("?" + urllib.parse.urlencode(query) if query else "")
        connection = http.client.HTTPConnection(self.netloc, timeout=60)
        try:
            connection.request(method, target, body=body, headers=headers or {})
            response = connection.getresponse()
            return response.status, response.read()
        finally:
            connection.close()

    def stop(self):
        self.process.send_signal(signal.SIGINT)
        code = self.process.wait(60)
        return code


@pytest.fixture
def studio():
    server = Studio()
    yield server
    if server.process.poll() is None:
        assert server.stop() == 0


async def session_of(studio, client):
    ws = await client.ws_connect(f"{studio.base}/api/session?token={studio.token}", origin=studio.base,
                                 max_msg_size=1 << 28)
    hello = await ws.receive_json(timeout=60)
    assert hello["type"] == "hello"
    return ws, hello["session"]


async def run_to_end(ws, deadline=600):
    """The frames and the last message of a run: (particles by index, counts seen, message)."""
    positions, counts = {}, []
    start = time.monotonic()
    while time.monotonic() - start < deadline:
        message = await ws.receive(timeout=deadline)
        if message.type == aiohttp.WSMsgType.BINARY:
            magic, count, first, done, total = FRAME.unpack_from(message.data)
            assert magic == b"DLAs" and len(message.data) == 32 + 16 * count
            xyz = struct.unpack_from(f"<{3 * count}f", message.data, 32)
            for i in range(count):
                positions[first + i] = xyz[3 * i:3 * i + 3]
            counts.append(len(positions))
        elif message.type == aiohttp.WSMsgType.TEXT:
            data = json.loads(message.data)
            if data["type"] in ("done", "error", "busy"):
                return positions, counts, data
        else:
            raise AssertionError(f"the socket ended: {message.type}")
    raise AssertionError("the run did not end")


def one_line(body):
    text = body.decode()
    return text.endswith("\n") and text.count("\n") == 1


# -- access ------------------------------------------------------------------------------------

def test_every_request_needs_the_token_the_host_and_the_origin(studio):
    assert studio.request("GET", "/")[0] == 200
    page = studio.request("GET", "/")[1].decode()
    assert studio.token in page and "{{token}}" not in page
    for name, (status, body) in {
        "no token": studio.request("GET", "/", token=False),
        "a wrong token": studio.request("GET", "/", query={"token": "x" * 43}),
        "an empty token": studio.request("GET", "/api/models", query={"token": ""}),
        "a rebinding Host": studio.request("GET", "/", headers={"Host": "evil.example:80"}),
        "another port's Host": studio.request("GET", "/", headers={"Host": "127.0.0.1:1"}),
        "another page's Origin": studio.request("GET", "/api/models", headers={"Origin": "http://evil.example"}),
        "a null Origin": studio.request("POST", "/api/bust", headers={"Origin": "null"}),
    }.items():
        assert status == 403 and one_line(body), (name, status, body)
    assert studio.request("GET", "/", headers={"Origin": studio.base})[0] == 200

    async def socket_from(origin):
        async with aiohttp.ClientSession() as client:
            try:
                ws = await client.ws_connect(f"{studio.base}/api/session?token={studio.token}", origin=origin)
                await ws.close()
                return 101
            except aiohttp.WSServerHandshakeError as e:
                return e.status
    assert asyncio.run(socket_from("http://evil.example")) == 403
    assert asyncio.run(socket_from(studio.base)) == 101


def test_loopback_unless_host_is_given(studio):
    # The default address is 127.0.0.1: nothing listens on another interface's address.
    assert studio.netloc.startswith("127.0.0.1:")
    port = int(studio.netloc.rsplit(":", 1)[1])
    out = subprocess.run(["ss", "-ltnH", f"sport = :{port}"], capture_output=True, text=True)
    if out.returncode == 0:
        assert all("127.0.0.1:" in line for line in out.stdout.splitlines() if line.strip()), out.stdout


def test_bad_command_lines_get_one_line():
    for words in (["--port", "70000"], ["--port", "-1"], ["--port", "x"], ["--host", ""], ["--host", "a b"],
                  ["--bogus"]):
        done = subprocess.run([DLA3D, "studio", *words], capture_output=True, text=True, timeout=60)
        assert done.returncode == 2 and done.stderr.startswith("dla3d: error: ") and done.stderr.count("\n") == 1, \
            (words, done.stderr)
    busy = Studio()
    try:
        port = busy.netloc.rsplit(":", 1)[1]
        done = subprocess.run([DLA3D, "studio", "--port", port], capture_output=True, text=True, timeout=60)
        assert done.returncode == 1 and "cannot listen" in done.stderr and done.stderr.count("\n") == 1, done.stderr
    finally:
        assert busy.stop() == 0


# -- the option panel's one description --------------------------------------------------------

def test_the_models_and_options_are_those_of_help(studio):
    status, body = studio.request("GET", "/api/models")
    assert status == 200
    described = {m["name"]: {o["name"] for o in m["options"]} for m in json.loads(body)["models"]}
    listed = json.loads(subprocess.run([DLA3D, "options"], capture_output=True, text=True, check=True).stdout)
    assert set(described) == {m["name"] for m in listed["models"]}
    assert {"grow", "colonize", "eden", "drop", "ballistic", "breakdown"} <= set(described)
    for model, options in described.items():
        words = [] if model == "grow" else [model]
        help_text = subprocess.run([DLA3D, *words, "--help"], capture_output=True, text=True, check=True).stdout
        # An option's line starts two spaces in; its help's further lines start far deeper.
        in_help = set(re.findall(r"^  (?:-[A-Za-z0-9],)?(--[a-z0-9][a-z0-9-]*)", help_text, re.M)) - {"--help", "--version"}
        assert in_help == options, (model, in_help ^ options)


# -- meshes and uploads ------------------------------------------------------------------------

def test_uploads_are_capped_and_read_by_the_library(studio, tmp_path):
    async def go():
        async with aiohttp.ClientSession() as client:
            ws, session = await session_of(studio, client)
            headers = {"Origin": studio.base}
            query = {"token": studio.token, "session": session}

            async def post(path, body, **extra):
                async with client.post(f"{studio.base}{path}", params={**query, **extra}, data=body,
                                       headers=headers) as r:
                    return r.status, await r.read()
            results = {
                "too big": await post("/api/mesh", b"\0" * ((64 << 20) + 1), type="stl"),
                "empty": await post("/api/mesh", b"", type="stl"),
                "no type": await post("/api/mesh", b"solid x\nendsolid x\n"),
                "a path for a type": await post("/api/mesh", b"solid x\n", type="../../etc/passwd"),
                "broken STL": await post("/api/mesh", b"\0" * 84 + b"\1" * 10, type="stl"),
                "truncated OFF": await post("/api/mesh", b"OFF\n8 12 0\n0 0 0\n", type="off"),
                "paint before a mesh": await post("/api/paint", b"ply\n"),
                "no session": await post("/api/mesh", b"x", type="stl", session="nope"),
            }
            for name, (status, body) in results.items():
                assert status in (400, 404, 409, 413) and one_line(body), (name, status, body)
            assert results["too big"][0] == 413
            assert results["no session"][0] == 404
            # A good upload: the repaired mesh comes back as binary STL.
            cube = "OFF\n8 12 0\n" + "".join(f"{x} {y} {z}\n" for x in (0, 9) for y in (0, 9) for z in (0, 9)) + \
                "".join(f"3 {a} {b} {c}\n" for a, b, c in [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5),
                                                           (0, 5, 1), (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4),
                                                           (1, 5, 7), (1, 7, 3)])
            status, stl = await post("/api/mesh", cube.encode(), type="off")
            assert status == 200 and len(stl) == 84 + 50 * 12
            status, body = await post("/api/paint", b"not a ply")
            assert status == 400 and one_line(body)
            # Downloads name a file of the session's folder, never a path.
            for name in ("../server.py", "/etc/passwd", "..", "", "mesh.stl/../../x", "%2e%2e"):
                async with client.get(f"{studio.base}/api/file", params={**query, "name": name}, headers=headers) as r:
                    assert r.status == 404 and one_line(await r.read()), name
            async with client.get(f"{studio.base}/api/file", params={**query, "name": "mesh.stl"}, headers=headers) as r:
                assert r.status == 200 and await r.read() == stl
            await ws.close()
    asyncio.run(go())


# -- runs --------------------------------------------------------------------------------------

def test_a_run_streams_and_its_files_are_the_commands(studio, tmp_path):
    async def go():
        async with aiohttp.ClientSession() as client:
            ws, session = await session_of(studio, client)
            await ws.send_json({"type": "grow", "model": "grow", "options": [["--particles", "30000"],
                                                                             ["--formats", "csv,json"]]})
            positions, counts, end = await run_to_end(ws)
            assert end["type"] == "done" and not end["stopped"], end
            assert end["command"] == ["dla3d", "--particles", "30000", "--formats", "csv,json", "--output", "run"]
            assert sorted(end["files"]) == ["run.csv", "run.json"]
            assert len(positions) == 30001 and counts[-1] == 30001
            async with client.get(f"{studio.base}/api/file", headers={"Origin": studio.base},
                                  params={"token": studio.token, "session": session, "name": "run.csv"}) as r:
                served = await r.read()
            await ws.close()
            return positions, served, end["command"]
    positions, served, command = asyncio.run(go())
    subprocess.run([DLA3D, *command[1:], "-q"], cwd=tmp_path, check=True, timeout=300)
    assert (tmp_path / "run.csv").read_bytes() == served, "the studio's CSV is not the command's"
    rows = served.decode().splitlines()[1:]
    for k in (0, 1, 777, len(rows) - 1):
        x, y, z = (float(v) for v in rows[k].split(",")[1:4])
        assert positions[k] == pytest.approx((x, y, z), rel=1e-6, abs=1e-5), k


def test_a_painted_eden_mask_is_the_commands_mask_file(studio, tmp_path):
    rows = [".....", "..x..", ".xox.", ".....", "....."]
    async def go():
        async with aiohttp.ClientSession() as client:
            ws, session = await session_of(studio, client)
            bad = [{"mask": [".x.", "xxq"]}, {"mask": ["xoo"]}, {"mask": ["..o"]}, {"mask": ["x"] * 18},
                   {"mask": "xo"}, {"mask": ["", "xo"]}, {"mask": rows, "model": "grow", "options": []},
                   {"mask": rows, "options": [["--mask", "A"]]}]
            for case in bad:
                await ws.send_json({"type": "grow", "model": "eden", "options": [["--mode", "drop"]], **case})
                reply = await ws.receive_json(timeout=60)
                assert reply["type"] == "error" and "\n" not in reply["line"], (case, reply)
            await ws.send_json({"type": "grow", "model": "eden", "mask": rows,
                                "options": [["--mode", "drop"], ["--sites", "3000"], ["--formats", "csv"]]})
            positions, _, end = await run_to_end(ws)
            assert end["type"] == "done" and not end["stopped"], end
            assert "--mask" in end["command"] and end["command"][end["command"].index("--mask") + 1] == "mask.txt"
            served = {}
            for name in ("run.csv", "mask.txt"):
                async with client.get(f"{studio.base}/api/file", headers={"Origin": studio.base},
                                      params={"token": studio.token, "session": session, "name": name}) as r:
                    assert r.status == 200, name
                    served[name] = await r.read()
            await ws.close()
            return positions, served, end["command"]
    positions, served, command = asyncio.run(go())
    assert served["mask.txt"].decode().splitlines()[1:] == rows
    (tmp_path / "mask.txt").write_bytes(served["mask.txt"])
    subprocess.run([DLA3D, *command[1:], "-q"], cwd=tmp_path, check=True, timeout=300)
    assert (tmp_path / "run.csv").read_bytes() == served["run.csv"], "the studio's CSV is not the command's"
    assert len(positions) == 3000
    # The painted mask is the one the run read: the paper's mask A grows another cluster.
    paper = ["A" if word == "mask.txt" else "paper" if word == "run" else word for word in command[1:]]
    subprocess.run([DLA3D, *paper, "-q"], cwd=tmp_path, check=True, timeout=300)
    assert (tmp_path / "paper.csv").read_bytes() != served["run.csv"]


def test_stop_keeps_what_grew_and_go_on_ends_as_the_uninterrupted_run(studio, tmp_path):
    """Stop, as soon as a partial frame arrived; Go on; the end equals one run of the command,
    for DLA (resumed from its checkpoint) and for another model (grown again from its seed)."""
    async def go(model, options):
        async with aiohttp.ClientSession() as client:
            ws, session = await session_of(studio, client)
            await ws.send_json({"type": "grow", "model": model, "options": options})
            stopped = False
            while True:
                message = await ws.receive(timeout=600)
                if message.type == aiohttp.WSMsgType.BINARY and not stopped:
                    await ws.send_json({"type": "stop"})
                    stopped = True
                elif message.type == aiohttp.WSMsgType.TEXT and json.loads(message.data)["type"] in ("done", "error"):
                    first_end = json.loads(message.data)
                    break
            assert first_end["type"] == "done", first_end
            await ws.send_json({"type": "goon"})
            positions, counts, end = await run_to_end(ws)
            assert end["type"] == "done" and not end["stopped"], end
            async with client.get(f"{studio.base}/api/file", headers={"Origin": studio.base},
                                  params={"token": studio.token, "session": session, "name": "run.csv"}) as r:
                served = await r.read()
            await ws.close()
            return first_end, served, end["command"]
    for model, options in (("grow", [["--particles", "200000"], ["--formats", "csv"]]),
                           ("eden", [["--sites", "300000"], ["--formats", "csv"]])):
        first_end, served, command = asyncio.run(go(model, options))
        folder = tmp_path / model
        folder.mkdir()
        subprocess.run([DLA3D, *command[1:], "-q"], cwd=folder, check=True, timeout=600)
        assert (folder / "run.csv").read_bytes() == served, f"{model}: Go on did not end as the command's run"
        if first_end["stopped"]:
            assert "run.csv" in first_end["files"]


def test_bad_options_get_one_line_each(studio):
    async def go():
        async with aiohttp.ClientSession() as client:
            ws, _ = await session_of(studio, client)
            cases = [
                {"type": "grow", "model": "nope"},
                {"type": "grow", "model": "grow", "options": [["--output", "/tmp/x"]]},
                {"type": "grow", "model": "grow", "options": [["--stl", "/etc/passwd"]]},
                {"type": "grow", "model": "grow", "options": [["--seed-mesh", "x.stl"]]},
                {"type": "grow", "model": "eden", "options": [["--mask", "/etc/passwd"]]},
                {"type": "grow", "model": "eden", "options": [["--mask", "run.ck"]]},
                {"type": "grow", "model": "grow", "options": [["--nope", "1"]]},
                {"type": "grow", "model": "grow", "options": [["--particles", "1"], ["--particles", "2"]]},
                {"type": "grow", "model": "grow", "options": "--particles 5"},
                {"type": "grow", "model": "grow", "options": [["--particles"]]},
                {"type": "grow", "model": "grow", "options": [["--quiet", ""]]},
                {"type": "grow", "model": "grow", "options": [["--particles", "x" * 2000]]},
                {"type": "grow", "model": "grow", "mesh": "mesh"},
                {"type": "goon"},
                {"type": "nonsense"},
                {"no": "type"},
            ]
            for case in cases:
                await ws.send_json(case)
                reply = await ws.receive_json(timeout=60)
                assert reply["type"] == "error" and "\n" not in reply["line"], (case, reply)
            for text in ("not json", "[1, 2]", "null"):
                await ws.send_str(text)
                reply = await ws.receive_json(timeout=60)
                assert reply["type"] == "error", (text, reply)
            # Out of range: the command line's own one-line refusal, and no files.
            for options in ([["--particles", "-1"]], [["--spacing", "0"]], [["--threads", "999"]],
                            [["--particles", "99999999999999"]], [["--eta", "11"]]):
                model = "breakdown" if options[0][0] == "--eta" else "grow"
                await ws.send_json({"type": "grow", "model": model, "options": options})
                _, _, end = await run_to_end(ws)
                assert end["type"] == "error" and "\n" not in end["line"] and end["files"] == [], (options, end)
            await ws.close()
    asyncio.run(go())


def test_a_client_that_goes_away_stops_its_run(studio):
    async def go():
        async with aiohttp.ClientSession() as client:
            ws, _ = await session_of(studio, client)
            await ws.send_json({"type": "grow", "model": "grow", "options": [["--particles", "5000000"]]})
            while (await ws.receive(timeout=120)).type != aiohttp.WSMsgType.BINARY:
                pass
            assert children(studio.pid), "no run under way"
            await ws.close()
    asyncio.run(go())
    # The event: the run's process is gone. Bounded by the count of looks, not by time.
    for _ in range(600):
        if not children(studio.pid):
            break
        select.select([], [], [], 0.05)
    assert not children(studio.pid), "the run outlived its client"


# -- abuse -------------------------------------------------------------------------------------

def test_fuzzed_requests_never_stop_the_studio_and_memory_stays_bounded(studio):
    rng = random.Random(69)
    paths = ["/", "/studio.js", "/api/models", "/api/session", "/api/mesh", "/api/bust", "/api/paint", "/api/file",
             "/api/nope", "/../../etc/passwd", "/%00", "/" + "a" * 5000, "//api//models"]
    methods = ["GET", "POST", "PUT", "DELETE", "HEAD", "OPTIONS", "PATCH"]

    def random_request():
        query = {}
        if rng.random() < 0.7:
            query["token"] = studio.token if rng.random() < 0.6 else rng.choice(["", "x", studio.token[:-1], "\0"])
        if rng.random() < 0.5:
            query["session"] = rng.choice(["", "x" * 300, "..", "0"])
        for key in rng.sample(["type", "name", "junk"], rng.randint(0, 3)):
            query[key] = rng.choice(["stl", "../x", "run.csv", "\u00e9" * 10, "", "off", "a" * 1000])
        headers = {}
        if rng.random() < 0.2:
            headers["Host"] = rng.choice(["evil.example", "", "127.0.0.1", studio.netloc + "x"])
        if rng.random() < 0.3:
            headers["Origin"] = rng.choice([studio.base, "http://evil.example", "null", ""])
        body = rng.choice([None, b"", os.urandom(rng.randint(1, 5000)), b"ply\n" + os.urandom(100), b"solid\n"])
        return rng.choice(methods), rng.choice(paths), body, headers, query

    # A first round grows the server's working set to its steady size.
    for _ in range(100):
        method, path, body, headers, query = random_request()
        status, reply = studio.request(method, path, body=body, headers=headers, token=False, query=query)
        assert status < 500, (method, path, query, headers, status, reply)
    before = rss_kib(studio.pid)
    for _ in range(400):
        method, path, body, headers, query = random_request()
        status, reply = studio.request(method, path, body=body, headers=headers, token=False, query=query)
        assert status < 500, (method, path, query, headers, status, reply)
    # Raw bytes: malformed HTTP.
    for raw in (b"GARBAGE\r\n\r\n", b"GET / HTTP/1.1\r\nHost: x\r\nContent-Length: -5\r\n\r\n",
                b"POST /api/mesh HTTP/1.1\r\nContent-Length: 99999999999\r\n\r\nabc", b"\0" * 1000 + b"\r\n\r\n",
                b"GET /" + b"a" * 100000 + b" HTTP/1.1\r\n\r\n"):
        import socket
        host, port = studio.netloc.rsplit(":", 1)
        with socket.create_connection((host, int(port)), timeout=30) as s:
            s.sendall(raw)
            s.shutdown(socket.SHUT_WR)
            try:
                s.recv(1000)
            except (ConnectionResetError, socket.timeout):
                pass
    assert studio.request("GET", "/api/models")[0] == 200, "the studio stopped answering"
    grown = rss_kib(studio.pid) - before
    assert grown < 30 * 1024, f"the server's memory grew by {grown} KiB over 400 requests"


def test_twenty_clients_at_once(studio):
    """Each connects, grows a small run and streams it: it gets its structure, or "busy"."""
    async def one(k, client):
        ws, _ = await session_of(studio, client)
        await ws.send_json({"type": "grow", "model": "grow",
                            "options": [["--particles", "3000"], ["--rng-seed", str(k)], ["--formats", "csv"]]})
        positions, _, end = await run_to_end(ws, deadline=300)
        await ws.close()
        return end["type"], len(positions)

    async def go():
        async with aiohttp.ClientSession() as client:
            return await asyncio.wait_for(asyncio.gather(*(one(k, client) for k in range(20))), 600)
    before = rss_kib(studio.pid)
    results = asyncio.run(go())
    kinds = [kind for kind, _ in results]
    assert set(kinds) <= {"done", "busy"}, results
    assert kinds.count("done") >= 1
    assert all(n == 3001 for kind, n in results if kind == "done"), results
    assert rss_kib(studio.pid) - before < 100 * 1024
    assert not children(studio.pid)


def test_ctrl_c_ends_the_studio_and_its_runs_and_folder(tmp_path):
    server = Studio()

    async def go():
        async with aiohttp.ClientSession() as client:
            ws, _ = await session_of(server, client)
            await ws.send_json({"type": "grow", "model": "grow", "options": [["--particles", "5000000"]]})
            while (await ws.receive(timeout=120)).type != aiohttp.WSMsgType.BINARY:
                pass
            runs = children(server.pid)
            assert runs
            assert server.stop() == 0
            return runs
    runs = asyncio.run(go())
    for pid in runs:
        assert not os.path.exists(f"/proc/{pid}") or open(f"/proc/{pid}/stat").read().split()[2] == "Z"
    leftover = [n for n in os.listdir(os.environ.get("TMPDIR", "/tmp")) if n.startswith("dla3d-studio-")]
    assert not any(str(server.pid) in n for n in leftover)


# -- the page, in a real browser ---------------------------------------------------------------

def browser_client():
    chromium = os.environ.get("CHROMIUM", "/usr/bin/chromium")
    script = os.path.join(CLIENTS, "studio_page.mjs")
    if not (shutil.which("node") and os.path.exists(chromium) and
            os.path.isdir(os.path.join(CLIENTS, "node_modules", "playwright-core"))):
        return None
    return script


def png_pixels(path):
    """A screenshot as an (height, width, 3) array of ints, by Pillow (matplotlib's reader)."""
    import numpy as np
    from PIL import Image
    with Image.open(path) as image:
        return np.asarray(image.convert("RGB"), dtype=np.int32)


@pytest.mark.skipif(browser_client() is None, reason="Chromium: needs chromium, node and Playwright "
                                                      "(the README's ci:clients step)")
def test_the_page_in_chromium_paints_grows_stops_goes_on_and_downloads(studio, tmp_path):
    import numpy as np
    done = subprocess.run(["node", browser_client(), studio.address, str(tmp_path), "20000"], capture_output=True,
                          text=True, timeout=900, cwd=CLIENTS)
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.split("DLA3D ", 1)[1])
    assert seen["messages"] == [] and seen["refused"] == [], seen
    assert seen["painted"], "the brush painted nothing"
    end = seen["end"]
    assert end["state"] == "done" and end["error"] == "", end
    # Particles appeared as they attached: at least three partial counts on the way.
    partial = {c for c in end["seen"] if 0 < c < end["count"]}
    assert len(partial) >= 3, end["seen"]
    assert seen["stopped"]["state"] == "stopped" and seen["stopped"]["count"] < end["count"], seen["stopped"]
    assert sorted(seen["saved"]) == ["mask.txt", "painted.ply", "run.csv", "run.glb"]
    # Eden's mask, painted on the grid: the site left of the dropped one and the one above it.
    eden = seen["eden"]
    assert eden["shown"] and eden["state"] == "done" and eden["count"] == 2000 and eden["error"] == "", eden
    assert "--mask mask.txt" in eden["command"], eden
    assert (tmp_path / "mask.txt").read_text().splitlines()[1:] == ["........."] * 3 + ["....x....", "...xo...."] + \
        ["........."] * 4
    # The shown command, run on the downloaded painted mesh, writes the same CSV.
    command = end["command"].split()
    assert command[0] == "dla3d" and "--seed-paint" in command and "painted.ply" in command, command
    again = tmp_path / "again"
    again.mkdir()
    shutil.copy(tmp_path / "painted.ply", again / "painted.ply")
    subprocess.run([DLA3D, *command[1:], "-q"], cwd=again, check=True, timeout=600)
    assert (again / "run.csv").read_bytes() == (tmp_path / "run.csv").read_bytes()
    rows = (tmp_path / "run.csv").read_text().splitlines()
    assert len(rows) - 1 == end["count"]
    # The glb passes Khronos' validator.
    validated = subprocess.run(["node", os.path.join(CLIENTS, "validate_gltf.mjs"), str(tmp_path / "run.glb")],
                               capture_output=True, text=True, timeout=300, cwd=CLIENTS)
    assert validated.returncode == 0 and validated.stdout.startswith("errors=0 "), validated.stdout + validated.stderr
    # The screenshot is not blank, and the structure shows inside the bust: the pixels that
    # changed from the painted bust before growth lie within the bust's own bounding box.
    before, after = png_pixels(tmp_path / "before.png"), png_pixels(tmp_path / "grown.png")
    assert before.shape == after.shape
    bust = np.any(before != before[0, 0], axis=2)  # the view's background is one colour
    assert bust.sum() > bust.size // 20, "the bust is not in view"
    ys, xs = np.nonzero(bust)
    changed = np.abs(after - before).sum(axis=2) > 60
    changed[:40] = False  # the count, drawn over the view's top left, changes too
    assert changed.sum() > bust.sum() // 20, "the structure does not show"
    inside = changed[ys.min():ys.max() + 1, xs.min():xs.max() + 1].sum()
    assert inside > 0.95 * changed.sum(), "the structure shows outside the bust"


@pytest.mark.skipif(browser_client() is None, reason="Chromium: needs chromium, node and Playwright "
                                                      "(the README's ci:clients step)")
def test_the_panel_shows_a_choice_as_a_drop_down_and_a_range_as_a_slider_with_a_preset(studio, tmp_path):
    done = subprocess.run(["node", os.path.join(CLIENTS, "studio_described.mjs"), studio.address, str(tmp_path)],
                          capture_output=True, text=True, timeout=600, cwd=CLIENTS)
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.split("DLA3D ", 1)[1])
    assert seen["messages"] == [], seen["messages"]
    controls = seen["controls"]
    # As `dla3d options` describes them: the field's choices in the library's order, eta's range.
    assert controls["field"] == {"tag": "SELECT", "choices": ["", "walkers", "conductor", "charges"]}, controls
    assert controls["eta"]["tag"] == "INPUT" and controls["eta"]["type"] == "text", controls
    assert controls["eta"]["label"].startswith("eta") and "--eta" in controls["eta"]["label"], controls
    assert controls["slider"] == {"type": "range", "min": "0", "max": "10", "value": "1"}, controls
    assert controls["strike"] == {"type": "checkbox", "checked": True}, controls
    # The preset's options, as the library's table has them, in the controls.
    assert seen["preset"] == {"eta": "3", "slider": "3", "seedAt": "0,40,0", "targetPlane": "y=-40",
                              "summary": "a bolt from a point 40 above to the ground 40 below (breakdown.md)"}, seen
    assert seen["etaWritten"] == "2.5"
    end = seen["end"]
    assert end["state"] == "done" and end["error"] == "", end
    for words in ["--eta 2.5", "--field conductor", "--seed-at 0,40,0", "--target-plane y=-40", "--radius pipe"]:
        assert words in end["command"], end["command"]
    # With no stop at the strike, growth goes on to its count (and the seed).
    assert end["count"] == 301, end
    # The check box, on by default, cleared: its negation.
    assert "--no-stop-at-strike" in end["command"], end["command"]


@pytest.mark.skipif(browser_client() is None, reason="Chromium: needs chromium, node and Playwright "
                                                      "(the README's ci:clients step)")
def test_the_page_draws_a_million_points(studio, tmp_path):
    # In the full tier (ctest -L full: python_studio_million), as its run takes a while.
    import numpy as np
    done = subprocess.run(["node", os.path.join(CLIENTS, "studio_million.mjs"), studio.address, str(tmp_path), "1000000"],
                          capture_output=True, text=True, timeout=1500, cwd=CLIENTS)
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.split("DLA3D ", 1)[1])
    assert seen["messages"] == [], seen["messages"]
    end = seen["end"]
    assert end["state"] == "done" and end["error"] == "" and end["count"] == 1000001, end  # and the seed
    assert end["command"] == "dla3d --particles 1000000 --formats csv --output run", end["command"]
    # Drawn as they came, not once at the end: many partial counts, rising.
    partial = [c for c in end["seen"] if 0 < c < end["count"]]
    assert len(set(partial)) >= 10 and partial == sorted(partial), end["seen"][:50]
    # The view shows the structure: much of it is not the background.
    view = png_pixels(tmp_path / "million.png")
    drawn = np.any(view != view[-1, -1], axis=2)
    drawn[:40] = False  # the count, drawn over the view's top left
    assert drawn.sum() > drawn.size // 10, drawn.sum()
