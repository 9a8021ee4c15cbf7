#!/usr/bin/env python3
"""Conformance runner: derive every cpfg model of the corpus with lsys and
compare with the strings cpfg itself derived (expected.str, and
expected.homo.str with --homomorphism); build every model (`lsys build`, as a
cpfg user would, in the model's folder) and report the ones that fail; with
--sheet, render a thumbnail of each and put them on one contact sheet.

Not part of `cargo test` (the corpus lives outside the repository and is
never copied in). Usage:

    scripts/cpfg-conformance.py [--lsys PATH] [--corpus DIR] [--markdown]
                                [--sheet FILE.png] [MODEL ...]

lsys prints with `--cpfg-format` (C's %g, as cpfg does). Both strings are
compared after removing all whitespace and rewriting every number as C's %g
(6 significant digits), which is how cpfg prints them.
Exit status 0 when every model with an expected string matches.
"""
import argparse
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

NUM = re.compile(r"-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def norm(text):
    s = re.sub(r"\s+", "", text)
    # Only numbers inside parameter lists: module names may contain digits.
    out = []
    depth = 0
    i = 0
    while i < len(s):
        c = s[i]
        if c == "(":
            depth += 1
        elif c == ")":
            depth = max(0, depth - 1)
        if depth > 0 and c not in "(),":
            m = NUM.match(s, i)
            if m and (i == 0 or s[i - 1] in "(,"):
                try:
                    v = float(m.group(0))
                    out.append("%g" % (0.0 if v == 0 else v))
                    i = m.end()
                    continue
                except ValueError:
                    pass
        out.append(c)
        i += 1
    return "".join(out)


def main_file(model_dir):
    return os.path.basename(model_dir).split("__")[-1] + ".l"


def first_line(text):
    for line in text.splitlines():
        line = re.sub(r"\x1b\[[0-9;]*[A-Za-z]", "", line).strip()
        if line:
            return line[:110]
    return ""


def needs_environment(d):
    """Whether cpfg runs the model with an environmental program (-e)."""
    try:
        spec = open(os.path.join(d, "specifications"), errors="replace").read()
    except OSError:
        return False
    return any("cpfg" in l and re.search(r"\s-e\s", l) for l in spec.splitlines())


def first_diff(a, b):
    n = min(len(a), len(b))
    for i in range(n):
        if a[i] != b[i]:
            return i
    return n


def run(lsys, d, main, homo, timeout):
    # --cpfg-format: lsys prints %g of the f32 itself. Its default (the f32's
    # shortest digits) rewritten as %g here would round twice and differ
    # from cpfg in the 6th digit whenever the shortest form ends in a 5.
    args = [lsys, "derive", "--cpfg-format", main] + (["--homomorphism"] if homo else [])
    try:
        p = subprocess.run(args, cwd=d, capture_output=True, text=True, timeout=timeout,
                           env=dict(os.environ, NO_COLOR="1"))
    except subprocess.TimeoutExpired:
        return None, "timed out after %ds" % timeout
    if p.returncode != 0:
        return None, first_line(p.stderr) or "exit %d" % p.returncode
    return p.stdout, None


def build(lsys, d, main, timeout):
    """`lsys build` in the model's folder: "ok", or the first line of why not."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "model.glb")
        try:
            p = subprocess.run([lsys, "build", main, "-o", out], cwd=d, capture_output=True,
                               text=True, timeout=timeout, env=dict(os.environ, NO_COLOR="1"))
        except subprocess.TimeoutExpired:
            return "timed out after %ds" % timeout
        if p.returncode != 0 or not os.path.exists(out):
            return first_line(p.stderr) or "exit %d" % p.returncode
    return "ok"


def render(lsys, d, main, png, size, timeout):
    """A thumbnail from the front (cpfg's usual view: +Y up); False if none."""
    try:
        p = subprocess.run([lsys, "render", main, "-o", png, "--view", "front", "--size",
                            "%dx%d" % (size, size)], cwd=d, capture_output=True, text=True,
                           timeout=timeout, env=dict(os.environ, NO_COLOR="1"))
    except subprocess.TimeoutExpired:
        return False
    return p.returncode == 0 and os.path.exists(png)


# --- a contact sheet without image libraries: PNG read/write with zlib ---

def read_png(path):
    """(width, height, rows of RGB bytes) of an 8-bit RGB or RGBA PNG."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, w = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            if depth != 8 or colour not in (2, 6):
                raise ValueError("%s: not 8-bit RGB(A)" % path)
            bpp = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(h):
        f, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        rows.append(bytes(line) if bpp == 3 else bytes(v for k, v in enumerate(line) if k % 4 != 3))
    return w, h, rows


def write_png(path, w, h, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


# 3x5 digits, to number the thumbnails as the table in docs/cpfg.md does.
DIGITS = ["111101101101111", "010110010010111", "111001111100111", "111001111001111",
          "101101111001001", "111100111001111", "111100111101111", "111001001001001",
          "111101111101111", "111101111001111"]


def contact_sheet(thumbs, size, cols, path):
    """`thumbs`: (number, png or None) in order; missing ones stay grey."""
    rows_n = (len(thumbs) + cols - 1) // cols
    W, H = cols * size, rows_n * size
    sheet = [bytearray(b"\xa0" * (W * 3)) for _ in range(H)]
    for k, (num, png) in enumerate(thumbs):
        ox, oy = (k % cols) * size, (k // cols) * size
        if png:
            w, h, rows = read_png(png)
            for y in range(min(h, size)):
                sheet[oy + y][ox * 3:(ox + min(w, size)) * 3] = rows[y][:min(w, size) * 3]
        for y in range(size):  # a one-pixel frame
            for x in (0, size - 1):
                sheet[oy + y][(ox + x) * 3:(ox + x) * 3 + 3] = b"\x60\x60\x60"
        for x in range(size):
            sheet[oy][(ox + x) * 3:(ox + x) * 3 + 3] = b"\x60\x60\x60"
        for i, ch in enumerate(str(num)):
            glyph = DIGITS[int(ch)]
            for gy in range(5):
                for gx in range(3):
                    if glyph[gy * 3 + gx] == "1":
                        for dy in range(2):
                            for dx in range(2):
                                px, py = ox + 4 + i * 8 + gx * 2 + dx, oy + 4 + gy * 2 + dy
                                sheet[py][px * 3:px * 3 + 3] = b"\x00\x00\x00"
    write_png(path, W, H, sheet)


def main():
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True,
                          text=True, cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip()
    ap = argparse.ArgumentParser()
    ap.add_argument("--lsys", default=os.path.join(root, "target/release/lsys"))
    ap.add_argument("--corpus", default=os.path.join(root, "../shared/corpus/cpfg"))
    ap.add_argument("--timeout", type=int, default=60)
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--no-build", action="store_true", help="skip `lsys build`")
    ap.add_argument("--sheet", help="render a thumbnail of every model into this contact sheet")
    ap.add_argument("--thumb", type=int, default=160, help="thumbnail size in pixels")
    ap.add_argument("models", nargs="*")
    a = ap.parse_args()
    corpus = os.path.abspath(a.corpus)
    rows = []
    for name in sorted(os.listdir(corpus)):
        d = os.path.join(corpus, name)
        if not os.path.isdir(d) or (a.models and not any(m in name for m in a.models)):
            continue
        main = main_file(d)
        chk = subprocess.run([a.lsys, "check", main], cwd=d, capture_output=True, text=True,
                             env=dict(os.environ, NO_COLOR="1"))
        check = "ok" if chk.returncode == 0 else first_line(chk.stderr)
        results = []
        for homo, exp_name in ((False, "expected.str"), (True, "expected.homo.str")):
            ep = os.path.join(d, exp_name)
            if not os.path.exists(ep):
                results.append("-")
                continue
            got, err = run(a.lsys, d, main, homo, a.timeout)
            if err:
                results.append("error: " + err)
                continue
            want = norm(open(ep).read())
            have = norm(got)
            if want == have:
                results.append("ok")
            else:
                k = first_diff(want, have)
                results.append("differs at %d: want %r got %r (lengths %d/%d)" % (
                    k, want[max(0, k - 15):k + 25], have[max(0, k - 15):k + 25], len(want), len(have)))
        env = needs_environment(d)
        built = "-" if a.no_build else build(a.lsys, d, main, a.timeout)
        rows.append((name, check, results[0], results[1], env, built))
    n = len(rows)
    n_check = sum(1 for r in rows if r[1] == "ok")
    with_exp = [r for r in rows if r[2] != "-" or r[3] != "-"]
    exact = [r for r in with_exp if all(x in ("ok", "-") for x in r[2:4])]
    no_env = [r for r in with_exp if not r[4]]
    exact_no_env = [r for r in exact if not r[4]]
    n_built = sum(1 for r in rows if r[5] == "ok")
    if a.markdown:
        print("| # | model | check | build | string | homomorphism | -e |")
        print("|---|---|---|---|---|---|---|")
        for k, r in enumerate(rows, 1):
            cells = [x.replace("|", "\\|")[:90] for x in (r[1], r[5], r[2], r[3])]
            print("| %d | %s | %s | %s |" % (k, r[0], " | ".join(cells), "yes" if r[4] else ""))
    else:
        for r in rows:
            print("%-70s check: %s%s\n    build: %s\n    str: %s\n    homo: %s" % (
                r[0], r[1], "  [environmental program]" if r[4] else "", r[5], r[2], r[3]))
    if not a.no_build:
        print("\n%d of %d models build" % (n_built, n))
        for r in rows:
            if r[5] != "ok":
                print("    build fails: %s: %s" % (r[0], r[5]))
    if a.sheet:
        with tempfile.TemporaryDirectory() as tmp:
            thumbs = []
            for k, r in enumerate(rows, 1):
                d = os.path.join(corpus, r[0])
                png = os.path.join(tmp, "%d.png" % k)
                ok = render(a.lsys, d, main_file(d), png, a.thumb, a.timeout)
                thumbs.append((k, png if ok else None))
            contact_sheet(thumbs, a.thumb, 10, a.sheet)
        print("contact sheet: %s (%d of %d rendered)" % (a.sheet, sum(1 for t in thumbs if t[1]), n))
    print("\n%d of %d models pass check; %d of %d models with expected strings derive them exactly"
          % (n_check, n, len(exact), len(with_exp)))
    print("without environmental programs (-e): %d of %d; with one: %d of %d" % (len(exact_no_env), len(no_env), len(exact) - len(exact_no_env), len(with_exp) - len(no_env)))
    return 0 if len(exact) == len(with_exp) else 1


if __name__ == "__main__":
    sys.exit(main())
