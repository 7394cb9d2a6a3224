#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""How long one request to the station takes while N idle TCP connections are open.

Opens N connections to a running `sewerplan serve` that send nothing (as any local program may,
without a token), then times one GET /api/maps (docs/operator-station.md, "Who may drive the
station"). With --trickle, each connection starts a request and sends a byte of its headers every
2 s, never ending them (each read within the station's 5 s read timeout): more of them than
`serve --max-connections` held every worker until the headers' deadline (10 s) cut them.
Usage: idle-connections.py PORT [N=200] [--trickle]
"""
import socket
import sys
import threading
import time
import urllib.request


def main():
    trickle = "--trickle" in sys.argv
    args = [a for a in sys.argv[1:] if a != "--trickle"]
    port = int(args[0])
    count = int(args[1]) if len(args) > 1 else 200
    started = time.monotonic()
    idle = [socket.create_connection(("127.0.0.1", port)) for _ in range(count)]
    opened = time.monotonic() - started
    done = threading.Event()
    cut = []
    if trickle:
        for s in idle:
            s.sendall(f"GET /api/maps HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Slow: ".encode())

        def send_bytes():
            while not done.wait(2):
                for s in idle:
                    try:
                        s.sendall(b"x")
                    except OSError:
                        pass

        threading.Thread(target=send_bytes, daemon=True).start()
    started = time.monotonic()
    urllib.request.urlopen(f"http://127.0.0.1:{port}/api/maps", timeout=300).read()
    answered = time.monotonic() - started
    done.set()
    if trickle:  # closed by the station (a sweep a second): readable, at its end, or reset
        time.sleep(1.5)
        for s in idle:
            s.setblocking(False)
            try:
                if s.recv(1) == b"":
                    cut.append(s)
            except BlockingIOError:
                pass
            except OSError:
                cut.append(s)
    print(f"{count} {'trickling' if trickle else 'idle'} connections opened in {opened:.3f} s; "
          f"GET /api/maps then answered in {answered:.3f} s"
          + (f"; {len(cut)} found closed by the station" if trickle else ""))
    for s in idle:
        s.close()


if __name__ == "__main__":
    main()
