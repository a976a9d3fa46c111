#!/usr/bin/env python3
"""Checks the relative links of the Markdown files under a directory (default: the
repository): each must name a file inside that directory, and a #fragment must name a
heading of the file it points to. Links that leave the directory (../ past its top,
absolute paths, file://) are errors: the repository, and an installed copy of its
documentation, must stand alone. Web links (http, https, mailto) are not followed.

    check_links.py [--missing-ok DIR/]... [ROOT]
        exit 1 listing each bad link as FILE:LINE: LINK: why; --missing-ok tolerates
        links to missing files under ROOT/DIR/ (an installed tree without the tests)
"""
import os
import re
import sys

SKIP_DIRS = {".git", "out", "__pycache__"}
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)", re.S)
FENCE = re.compile(r"^(```|~~~).*?^\1", re.S | re.M)
CODE = re.compile(r"`[^`\n]*`")


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[`*_]", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    out = set()
    with open(path, encoding="utf-8") as f:
        text = FENCE.sub("", f.read())
    for m in re.finditer(r"^#{1,6}\s+(.*?)\s*#*\s*$", text, re.M):
        out.add(slug(m.group(1)))
    return out


def blank(match):
    """Replaces code with spaces but keeps newlines, so line numbers stay right."""
    return re.sub(r"[^\n]", " ", match.group(0))


def check(root, missing_ok):
    root = os.path.realpath(root)
    errors = 0
    for top, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("build"))
        for name in sorted(files):
            if not name.endswith(".md"):
                continue
            path = os.path.join(top, name)
            with open(path, encoding="utf-8") as f:
                text = CODE.sub(blank, FENCE.sub(blank, f.read()))
            for m in LINK.finditer(text):
                target = m.group(1)
                line = text.count("\n", 0, m.start(1)) + 1
                where = f"{os.path.relpath(path, root)}:{line}: {target}"
                if re.match(r"(https?|mailto):", target):
                    continue
                file_part, _, fragment = target.partition("#")
                if re.match(r"[a-z]+:", file_part) or file_part.startswith("/"):
                    print(f"{where}: points outside the repository")
                    errors += 1
                    continue
                dest = os.path.realpath(os.path.join(top, file_part)) if file_part else path
                if os.path.commonpath([root, dest]) != root:
                    print(f"{where}: points outside {root}")
                    errors += 1
                elif not os.path.exists(dest):
                    if any(os.path.relpath(dest, root).startswith(d) for d in missing_ok):
                        continue
                    print(f"{where}: no such file")
                    errors += 1
                elif fragment and dest.endswith(".md") and fragment not in anchors(dest):
                    print(f"{where}: no heading #{fragment} in {os.path.relpath(dest, root)}")
                    errors += 1
    return errors


def main():
    args, missing_ok = sys.argv[1:], []
    while len(args) >= 2 and args[0] == "--missing-ok":
        missing_ok.append(args[1])
        args = args[2:]
    root = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    errors = check(root, missing_ok)
    if errors:
        print(f"{errors} bad link(s)")
    sys.exit(1 if errors else 0)


if __name__ == "__main__":
    main()
