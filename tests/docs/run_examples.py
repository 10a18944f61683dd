#!/usr/bin/env python3
"""Runs the examples of README.md and docs/*.md as a reader would, and checks the docs' links.

usage: run_examples.py --source SRC --build BUILD [--python PY] [--only NAME_PART]

The conventions (docs/design.md, "The examples test"):
- every line of a ```sh block runs with bash, in document order, in one scratch folder per page
  that looks like the checkout (build/ -> the build folder, ../shared -> the shared folder), with
  build/app first on PATH; a line ending in a backslash continues on the next;
- it must exit with 0, or with N when its comment is `# exit N`;
- `# slow` lines run only with ISOCURV_DOCS_SLOW=1; `# display` and `# skip` lines never run;
- a ```python block runs as one script with the interpreter the module was built for; without
  the module (a sanitizer build) it is skipped, and so is the rest of its page, whose commands
  may read what it wrote;
- a line naming ../shared/datasets is skipped when the shared datasets are missing.
Also: every relative link (file and #anchor) resolves, the README links every docs/ page, and
every command's --help ends with "Docs: docs/PAGE.md" naming a page that exists.
Exit status 0 when everything passed, 1 otherwise.
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

MARKER = re.compile(r"^#\s*(slow|display|skip|exit\s+(\d+))\b")
LINK = re.compile(r"\]\(([^)\s]+)\)")
TIMEOUT_S = 600


def comment_of(line):
    """The bash comment of `line` (from its first unquoted '#' after a blank), or ''."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            if c == quote:
                quote = None
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1] in " \t"):
            return line[i:]
    return ""


def blocks(path):
    """(language, first line number, lines) for each fenced block of a markdown file."""
    out, lang, start, body = [], None, 0, []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            stripped = line.rstrip("\n")
            if stripped.startswith("```"):
                if lang is None:
                    lang, start, body = stripped[3:].strip() or "text", n + 1, []
                else:
                    out.append((lang, start, body))
                    lang = None
            elif lang is not None:
                body.append(stripped)
    return out


def commands(start, lines):
    """(line number, command) for each command of a sh block, continuation lines joined."""
    out, pending, first = [], "", start
    for n, line in enumerate(lines, start):
        if not pending:
            first = n
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        cmd = (pending + line).strip()
        pending = ""
        if cmd and not cmd.startswith("#"):
            out.append((first, cmd))
    return out


def slug(heading):
    """GitHub's anchor for a heading's text."""
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(path):
    seen, out, in_code = {}, set(), False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("```"):
                in_code = not in_code
                continue
            m = None if in_code else re.match(r"^#{1,6}\s+(.*)$", line)
            if m:
                s = slug(m.group(1))
                n = seen.get(s, 0)
                seen[s] = n + 1
                out.add(s if n == 0 else f"{s}-{n}")
    return out


def check_links(pages, problems):
    for page in pages:
        text, in_code, kept = open(page, encoding="utf-8").read().split("\n"), False, []
        for line in text:  # links inside code blocks are not links
            if line.startswith("```"):
                in_code = not in_code
            elif not in_code:
                kept.append(line)
        body = "\n".join(kept)
        for target in LINK.findall(body) + re.findall(r'src="([^"]+)"', body):
            if re.match(r"^[a-z]+:", target):
                continue  # http:, https:, mailto:
            file_part, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(page), file_part)) if file_part else page
            if not os.path.exists(dest):
                problems.append(f"{os.path.relpath(page)}: link to missing {target}")
            elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
                problems.append(f"{os.path.relpath(page)}: link to missing anchor {target}")


def check_help(isocurv, source, problems):
    top = subprocess.run([isocurv, "--help"], capture_output=True, text=True).stdout
    names = re.findall(r"^\s{2}(\w+)\s", top.split("SUBCOMMANDS:")[-1], re.M)
    if len(names) < 10:
        problems.append(f"isocurv --help lists only {names}")
    for name in names:
        r = subprocess.run([isocurv, name, "--help"], capture_output=True, text=True)
        last = [l for l in r.stdout.splitlines() if l.strip()][-1:] or [""]
        m = re.match(r"^Docs: (docs/\S+\.md)$", last[0].strip())
        if r.returncode != 0 or not m:
            problems.append(f"isocurv {name} --help does not end with 'Docs: docs/PAGE.md' "
                            f"(last line: {last[0]!r})")
        elif not os.path.exists(os.path.join(source, m.group(1))):
            problems.append(f"isocurv {name} --help names {m.group(1)}, which does not exist")
    print(f"help: {len(names)} commands checked")


def check_gallery(readme, script, problems):
    """Every command of the README's gallery is in scripts/make_pictures.sh, word for word, and
    every picture the gallery shows is one the script makes."""
    text = open(readme, encoding="utf-8").read()
    gallery = text.split("## Gallery", 1)[-1].split("\n## ", 1)[0]
    made = open(script, encoding="utf-8").read()
    shown = re.findall(r'src="docs/pictures/([^"]+)"', gallery)
    cmds = [c for _, c in commands(0, [l for l in gallery.splitlines() if l.startswith("isocurv ")])]
    if len(shown) != 4 or len(cmds) < 4:
        problems.append(f"README gallery: {len(shown)} pictures and {len(cmds)} commands, not 4")
    for c in cmds:
        if f"'{c}'" not in made:
            problems.append(f"README gallery command not in scripts/make_pictures.sh: {c}")
    for p in shown:
        if p not in made:
            problems.append(f"README gallery picture {p} is not made by scripts/make_pictures.sh")


def scratch_checkout(build, source, root):
    """A folder that looks like the checkout: build/ and scripts/ links, ../shared beside it."""
    work = os.path.join(root, "checkout")
    os.makedirs(work)
    os.symlink(os.path.abspath(build), os.path.join(work, "build"))
    os.symlink(os.path.join(source, "scripts"), os.path.join(work, "scripts"))
    shared = os.path.normpath(os.path.join(source, "..", "shared"))
    if os.path.isdir(shared):
        os.symlink(shared, os.path.join(root, "shared"))
    return work


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--python", default="/usr/bin/python3")
    ap.add_argument("--only", default="", help="run the pages whose file name holds this text")
    a = ap.parse_args()
    source, build = os.path.abspath(a.source), os.path.abspath(a.build)
    isocurv = os.path.join(build, "app", "isocurv")
    slow = os.environ.get("ISOCURV_DOCS_SLOW") == "1"
    have_shared = os.path.isdir(os.path.join(source, "..", "shared", "datasets"))
    have_module = (bool(glob.glob(os.path.join(build, "python", "isocurv*.so")))
                   and os.environ.get("ISOCURV_DOCS_NO_PYTHON") != "1")
    pages = [os.path.join(source, "README.md")] + sorted(glob.glob(os.path.join(source, "docs", "*.md")))
    problems, ran, skipped = [], 0, 0

    check_links(pages, problems)
    readme = open(pages[0], encoding="utf-8").read()
    for page in pages[1:]:
        if "docs/" + os.path.basename(page) not in readme:
            problems.append(f"README.md does not link docs/{os.path.basename(page)}")
    check_help(isocurv, source, problems)
    check_gallery(pages[0], os.path.join(source, "scripts", "make_pictures.sh"), problems)

    env = dict(os.environ)
    env["PATH"] = os.path.join(build, "app") + os.pathsep + env.get("PATH", "")
    env["PYTHONPATH"] = os.path.join(build, "python")
    for page in pages:
        rel = os.path.relpath(page, source)
        if a.only and a.only not in rel:
            continue
        root = tempfile.mkdtemp(prefix="isocurv-docs-")
        try:
            work = scratch_checkout(build, source, root)
            python_skipped = False  # the rest of the page may need what a skipped block wrote
            for lang, start, body in blocks(page):
                if python_skipped and lang in ("python", "sh"):
                    print(f"{rel}:{start}: skipped (after a skipped Python block)")
                    skipped += 1
                    continue
                if lang == "python":
                    if not have_module:
                        print(f"{rel}:{start}: skipped (no Python module)")
                        skipped += 1
                        python_skipped = True
                        continue
                    if "../shared/datasets" in "\n".join(body) and not have_shared:
                        print(f"{rel}:{start}: skipped (no shared datasets)")
                        skipped += 1
                        continue
                    script = os.path.join(work, f"example_{start}.py")
                    with open(script, "w") as f:
                        f.write("\n".join(body) + "\n")
                    jobs = [(start, [a.python, script], "python block", 0)]
                elif lang == "sh":
                    jobs = []
                    for n, cmd in commands(start, body):
                        m = MARKER.match(comment_of(cmd).strip())
                        kind = m.group(1).split()[0] if m else ""
                        if kind in ("display", "skip") or (kind == "slow" and not slow):
                            print(f"{rel}:{n}: skipped ({kind}): {cmd}")
                            skipped += 1
                            continue
                        if "../shared/datasets" in cmd and not have_shared:
                            print(f"{rel}:{n}: skipped (no shared datasets): {cmd}")
                            skipped += 1
                            continue
                        want = int(m.group(2)) if m and m.group(2) else 0
                        jobs.append((n, ["bash", "-c", cmd], cmd, want))
                else:
                    continue
                for n, argv, label, want in jobs:
                    t0 = time.time()
                    try:
                        r = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True,
                                           timeout=TIMEOUT_S)
                        rc, err = r.returncode, (r.stderr or r.stdout).strip().splitlines()[-3:]
                    except subprocess.TimeoutExpired:
                        rc, err = "timeout", []
                    ran += 1
                    ok = rc == want
                    print(f"{rel}:{n}: {'ok' if ok else 'FAILED'} ({time.time() - t0:.1f} s): {label}")
                    if not ok:
                        problems.append(f"{rel}:{n}: exit {rc}, expected {want}: {label}\n    "
                                        + "\n    ".join(err))
        finally:
            shutil.rmtree(root, ignore_errors=True)

    print(f"{ran} examples run, {skipped} skipped")
    for p in problems:
        print("PROBLEM: " + p)
    return 1 if problems or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
