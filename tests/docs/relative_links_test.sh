#!/usr/bin/env bash
# Every relative link of README.md and docs/*.md leads to a file or folder of the repository, and
# every #anchor of a link into a Markdown file names one of its headings (as GitHub makes anchors
# from headings: lower case, punctuation dropped, spaces as hyphens). Links inside code are not
# links and are not checked.
#   tests/docs/relative_links_test.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
cd "$source_dir"
python3 - README.md docs/*.md <<'PYTHON'
import os, re, sys

def strip_code(text):
    text = re.sub(r"(?ms)^```.*?^```", "", text)
    return re.sub(r"`[^`\n]*`", "", text)

def anchors(path):
    slugs = set()
    with open(path, encoding="utf-8") as f:
        body = re.sub(r"(?ms)^```.*?^```", "", f.read())
    for heading in re.findall(r"(?m)^#+ +(.*?) *#*$", body):
        slug = re.sub(r"[^\w\- ]", "", heading.replace("`", "").lower()).replace(" ", "-")
        slugs.add(slug)
    return slugs

failures = []
checked = 0
for page in sys.argv[1:]:
    with open(page, encoding="utf-8") as f:
        text = strip_code(f.read())
    for target in re.findall(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", text):
        if re.match(r"[a-z]+:", target):
            continue  # http:, https:, mailto:
        checked += 1
        path, _, anchor = target.partition("#")
        resolved = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
        if not os.path.exists(resolved):
            failures.append(f"{page}: link {target}: {resolved} does not exist")
        elif anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
            failures.append(f"{page}: link {target}: {resolved} has no heading for #{anchor}")
for failure in failures:
    print("FAIL:", failure, file=sys.stderr)
if failures:
    sys.exit(1)
print(f"PASS: {checked} relative links of {len(sys.argv) - 1} pages resolve")
PYTHON
