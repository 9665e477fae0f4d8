#!/usr/bin/env bash
# Every relative link in README.md and docs/ (docs/*.md, docs/gallery/README.md) points at a file
# or folder of the repository, and a link's #anchor at a heading of the Markdown file it names
# (GitHub's heading ids). Links inside code spans and code blocks are not links. A broken one
# prints FILE:LINE: link. Args: <polarview executable (unused)> <repository root>.
set -u
cd "$2" || exit 1
python3 - README.md docs/*.md docs/gallery/README.md <<'EOF'
import os, re, sys

def heading_ids(path):
    ids, seen, fenced = set(), {}, False
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            fenced = not fenced
        m = None if fenced else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            base = re.sub(r"[^\w\- ]", "", m.group(1).lower()).replace(" ", "-")
            n = seen.get(base, 0)
            seen[base] = n + 1
            ids.add(base if n == 0 else f"{base}-{n}")
    return ids

failures = 0
for source in sys.argv[1:]:
    fenced = False
    for number, line in enumerate(open(source, encoding="utf-8"), 1):
        if line.startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            continue
        text = re.sub(r"`[^`]*`", "", line)  # code spans hold no links
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target):
                continue  # http:, https:, mailto:
            path, _, anchor = target.partition("#")
            resolved = os.path.normpath(os.path.join(os.path.dirname(source), path)) if path else source
            problem = None
            if not os.path.exists(resolved):
                problem = "no such file"
            elif anchor and resolved.endswith(".md") and anchor not in heading_ids(resolved):
                problem = f"no heading #{anchor} in {resolved}"
            if problem:
                print(f"FAIL: {source}:{number}: ({target}): {problem}")
                failures += 1
print(f"doc_links: {failures} broken" if failures else "doc_links: ok")
sys.exit(1 if failures else 0)
EOF
