#!/usr/bin/env python3
"""Conformance runner: derive every cpfg model of the corpus with lsys and
compare with the strings cpfg itself derived (expected.str, and
expected.homo.str with --homomorphism).

Not part of `cargo test` (the corpus lives outside the repository and is
never copied in). Usage:

    scripts/cpfg-conformance.py [--lsys PATH] [--corpus DIR] [--markdown]

lsys prints with `--cpfg-format` (C's %g, as cpfg does). Both strings are
compared after removing all whitespace and rewriting every number as C's %g
(6 significant digits), which is how cpfg prints them.
Exit status 0 when every model with an expected string matches.
"""
import argparse
import os
import re
import subprocess
import sys

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


def main():
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True,
                          text=True, cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip()
    ap = argparse.ArgumentParser()
    ap.add_argument("--lsys", default=os.path.join(root, "target/release/lsys"))
    ap.add_argument("--corpus", default=os.path.join(root, "../shared/corpus/cpfg"))
    ap.add_argument("--timeout", type=int, default=60)
    ap.add_argument("--markdown", action="store_true")
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
        rows.append((name, check, results[0], results[1], env))
    n = len(rows)
    n_check = sum(1 for r in rows if r[1] == "ok")
    with_exp = [r for r in rows if r[2] != "-" or r[3] != "-"]
    exact = [r for r in with_exp if all(x in ("ok", "-") for x in r[2:4])]
    no_env = [r for r in with_exp if not r[4]]
    exact_no_env = [r for r in exact if not r[4]]
    if a.markdown:
        print("| model | check | string | homomorphism | -e |")
        print("|---|---|---|---|---|")
        for r in rows:
            cells = [x.replace("|", "\\|")[:90] for x in r[1:4]] + ["yes" if r[4] else ""]
            print("| %s | %s |" % (r[0], " | ".join(cells)))
    else:
        for r in rows:
            print("%-70s check: %s%s\n    str: %s\n    homo: %s" % (
                r[0], r[1], "  [environmental program]" if r[4] else "", r[2], r[3]))
    print("\n%d of %d models pass check; %d of %d models with expected strings derive them exactly"
          % (n_check, n, len(exact), len(with_exp)))
    print("without environmental programs (-e): %d of %d; with one: %d of %d" % (len(exact_no_env), len(no_env), len(exact) - len(exact_no_env), len(with_exp) - len(no_env)))
    return 0 if len(exact) == len(with_exp) else 1


if __name__ == "__main__":
    sys.exit(main())
