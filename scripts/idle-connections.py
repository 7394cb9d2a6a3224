#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""How long one request to the station takes while N idle TCP connections are open.

Opens N connections to a running `sewerplan serve` that send nothing (as any local program may,
without a token), then times one GET /api/maps (docs/operator-station.md, "Who may drive the
station"). Usage: idle-connections.py PORT [N=200]
"""
import socket
import sys
import time
import urllib.request


def main():
    port = int(sys.argv[1])
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    started = time.monotonic()
    idle = [socket.create_connection(("127.0.0.1", port)) for _ in range(count)]
    opened = time.monotonic() - started
    started = time.monotonic()
    urllib.request.urlopen(f"http://127.0.0.1:{port}/api/maps", timeout=300).read()
    answered = time.monotonic() - started
    print(f"{count} idle connections opened in {opened:.3f} s; "
          f"GET /api/maps then answered in {answered:.3f} s")
    for s in idle:
        s.close()


if __name__ == "__main__":
    main()
