"""The studio's cost against the command line's: the same DLA grown by `dla3d` and by a studio
session (started by `dla3d studio`, driven over its WebSocket as the page drives it, every frame
received), timed from the request to the last message. Runs alternate, and the medians and
their ratio are printed (docs/performance.md).

    /usr/bin/python3 bench/studio_overhead.py --dla3d build/dla3d [-n 1000000] [--runs 3]
"""

import argparse
import asyncio
import json
import os
import select
import statistics
import subprocess
import tempfile
import time
import urllib.parse

import aiohttp


async def grow_in_studio(base, token, options):
    async with aiohttp.ClientSession() as client:
        ws = await client.ws_connect(f"{base}/api/session?token={token}", origin=base, max_msg_size=1 << 28)
        assert (await ws.receive_json())["type"] == "hello"
        start = time.perf_counter()
        await ws.send_json({"type": "grow", "model": "grow", "options": options})
        received = 0
        while True:
            message = await ws.receive(timeout=3600)
            if message.type == aiohttp.WSMsgType.BINARY:
                received += int.from_bytes(message.data[4:8], "little")
            elif message.type == aiohttp.WSMsgType.TEXT and json.loads(message.data)["type"] in ("done", "error", "busy"):
                end = json.loads(message.data)
                break
        seconds = time.perf_counter() - start
        await ws.close()
        assert end["type"] == "done", end
        return seconds, received


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--dla3d", default="build/dla3d")
    parser.add_argument("-n", type=int, default=1000000)
    parser.add_argument("--runs", type=int, default=3)
    options = parser.parse_args()
    options.dla3d = os.path.abspath(options.dla3d)  # the command line runs in a folder of its own
    studio = subprocess.Popen([options.dla3d, "studio", "--port", "0"], stdout=subprocess.PIPE, text=True)
    try:
        select.select([studio.stdout], [], [], 60)
        address = urllib.parse.urlparse(studio.stdout.readline().split(": ", 1)[1].strip())
        base, token = f"http://{address.netloc}", urllib.parse.parse_qs(address.query)["token"][0]
        cli, web = [], []
        with tempfile.TemporaryDirectory() as folder:
            for run in range(options.runs):
                words = ["--particles", str(options.n), "--rng-seed", str(100 + run), "--formats", "csv,json"]
                start = time.perf_counter()
                subprocess.run([options.dla3d, *words, "-q", "-o", "run"], cwd=folder, check=True)
                cli.append(time.perf_counter() - start)
                seconds, received = asyncio.run(grow_in_studio(base, token, [list(p) for p in zip(words[::2], words[1::2])]))
                assert received == options.n + 1, received
                web.append(seconds)
                print(f"run {run}: dla3d {cli[-1]:.2f} s, studio {web[-1]:.2f} s", flush=True)
        a, b = statistics.median(cli), statistics.median(web)
        print(f"{options.n} particles, medians of {options.runs}: dla3d {a:.2f} s, studio {b:.2f} s, ratio {b / a:.3f}")
    finally:
        studio.terminate()
        studio.wait()


if __name__ == "__main__":
    main()
