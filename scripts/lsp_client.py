#!/usr/bin/env python3
"""A minimal LSP client for `lsys lsp` over stdio: opens a grammar, waits
for its diagnostics, asks for a hover, edits it and waits again, and
prints the latency of each. With `--generate N`, writes a grammar of about
N lines first (defines, productions over them, an include) and opens that.

    python3 scripts/lsp_client.py [--lsys target/debug/lsys] [--generate 1000] [FILE]
"""
import argparse, json, os, subprocess, sys, tempfile, time


class Client:
    def __init__(self, cmd):
        self.p = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.next = 0

    def send(self, msg):
        body = json.dumps(msg).encode()
        self.p.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.p.stdin.flush()

    def read(self):
        length = 0
        while True:
            line = self.p.stdout.readline()
            if not line:
                raise EOFError("server closed")
            if line in (b"\r\n", b"\n"):
                break
            k, _, v = line.decode().partition(":")
            if k.lower() == "content-length":
                length = int(v)
        return json.loads(self.p.stdout.read(length))

    def request(self, method, params):
        self.next += 1
        self.send({"jsonrpc": "2.0", "id": self.next, "method": method, "params": params})
        while True:
            m = self.read()
            if m.get("id") == self.next and "method" not in m:
                return m.get("result", m.get("error"))

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def diagnostics(self, version):
        while True:
            m = self.read()
            if m.get("method") == "textDocument/publishDiagnostics" and m["params"].get("version") == version:
                return m["params"]["diagnostics"]


def generate(path, n):
    lines = ["#include \"gen_shared.lsys\"", "derivation length: 6", "axiom: M0(1)"]
    k = max(1, (n - 3) // 3)
    lines += [f"#define K{i} {i % 7 + 1}" for i in range(k)]
    for i in range(k):
        nxt = (i + 1) % k
        lines.append(f"M{i}(x) : x < K{i} --> F(x) [+(K{i}) M{nxt}(x+1)] S(LEN)")
        lines.append(f"M{i}(x) --> F(LEN) M{nxt}(x)")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(os.path.dirname(path), "gen_shared.lsys"), "w") as f:
        f.write("#define LEN 2\nS(a) --> F(a)\n")
    return len(lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lsys", default="target/debug/lsys")
    ap.add_argument("--generate", type=int)
    ap.add_argument("--edits", type=int, default=10)
    ap.add_argument("file", nargs="?")
    a = ap.parse_args()
    path = a.file
    if a.generate:
        path = os.path.join(tempfile.mkdtemp(), "gen.lsys")
        print(f"generated {generate(path, a.generate)} lines: {path}")
    path = os.path.abspath(path)
    uri = "file://" + path
    text = open(path).read()
    c = Client([a.lsys, "lsp"])
    t = time.perf_counter()
    c.request("initialize", {"processId": os.getpid(), "capabilities": {}, "rootUri": None})
    c.notify("initialized", {})
    print(f"initialize: {1000 * (time.perf_counter() - t):.1f} ms")
    t = time.perf_counter()
    c.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "lsys", "version": 1, "text": text}})
    d = c.diagnostics(1)
    print(f"open -> diagnostics ({len(d)}): {1000 * (time.perf_counter() - t):.1f} ms")
    for x in d[:3]:
        print("  ", x["range"]["start"], x.get("code"), x["message"].splitlines()[0])
    lines = text.split("\n")
    line = next((i for i, l in enumerate(lines) if "-->" in l), 0)
    t = time.perf_counter()
    h = c.request("textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": line, "character": 0}})
    print(f"hover: {1000 * (time.perf_counter() - t):.1f} ms")
    if h:
        print("  ", h["contents"]["value"].splitlines()[0])
    # Keystrokes: insert and delete a space at the end of the first production line.
    times = []
    for v in range(2, 2 + a.edits):
        col = len(lines[line])
        change = {"range": {"start": {"line": line, "character": col}, "end": {"line": line, "character": col}}, "text": " "} \
            if v % 2 == 0 else \
            {"range": {"start": {"line": line, "character": col}, "end": {"line": line, "character": col + 1}}, "text": ""}
        t = time.perf_counter()
        c.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": v}, "contentChanges": [change]})
        c.diagnostics(v)
        times.append(1000 * (time.perf_counter() - t))
    times.sort()
    print(f"edit -> diagnostics over {len(times)} edits: median {times[len(times) // 2]:.1f} ms, max {times[-1]:.1f} ms")
    for method in ["textDocument/semanticTokens/full", "textDocument/documentSymbol", "textDocument/codeLens"]:
        t = time.perf_counter()
        r = c.request(method, {"textDocument": {"uri": uri}})
        size = len(r["data"]) // 5 if isinstance(r, dict) and "data" in r else len(r or [])
        print(f"{method}: {1000 * (time.perf_counter() - t):.1f} ms ({size} items)")
    c.request("shutdown", None)
    c.notify("exit", None)
    c.p.wait(timeout=10)
    print(f"exit code {c.p.returncode}")


if __name__ == "__main__":
    main()
