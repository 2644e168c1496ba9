#!/usr/bin/env python3
"""A static file server on loopback for the streaming viewer's HTTP tests.

Serves DIRECTORY on 127.0.0.1 at a free port and prints that port on the first line of stdout.
--status PATH=CODE answers PATH (as requested, e.g. /city/b3.png) with that HTTP status and no
body; --delay SECONDS waits that long before each answer (a slow server). Runs until killed.
"""
import argparse
import functools
import http.server
import sys
import time


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--directory", required=True)
    parser.add_argument("--status", action="append", default=[], metavar="PATH=CODE")
    parser.add_argument("--delay", type=float, default=0.0)
    args = parser.parse_args()
    statuses = {path: int(code) for path, code in (s.split("=", 1) for s in args.status)}

    class Handler(http.server.SimpleHTTPRequestHandler):
        def do_GET(self):
            time.sleep(args.delay)
            if self.path in statuses:
                self.send_response(statuses[self.path])
                self.send_header("Content-Length", "0")
                self.end_headers()
                return
            super().do_GET()

        def log_message(self, *unused):
            pass

    server = http.server.ThreadingHTTPServer(
        ("127.0.0.1", 0), functools.partial(Handler, directory=args.directory))
    print(server.server_address[1], flush=True)
    server.serve_forever()


if __name__ == "__main__":
    sys.exit(main())
