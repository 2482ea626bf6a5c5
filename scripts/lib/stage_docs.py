"""Stages the docs site's sources (scripts/docs): README.md (the home page), BENCHMARKS.md and
docs/ at their paths in the repository, and every file of the repository that a staged page
links to by a relative path (a source file, the notebook, another Markdown page), so that a link
that works on the repository's web view works on the site too. A relative link to a file that
does not exist is an error that names the page and the link.

    python stage_docs.py REPO STAGE
"""

import pathlib
import re
import shutil
import sys

LINK = re.compile(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)|<img [^>]*src=\"([^\"]+)\"")


def main() -> int:
    repo = pathlib.Path(sys.argv[1]).resolve()
    stage = pathlib.Path(sys.argv[2]).resolve()
    if stage.exists():
        shutil.rmtree(stage)
    stage.mkdir(parents=True)
    todo = [repo / "README.md", repo / "BENCHMARKS.md", *sorted((repo / "docs").rglob("*"))]
    seen = set()
    broken = []
    while todo:
        src = todo.pop()
        if src in seen or src.is_dir():
            continue
        seen.add(src)
        dst = stage / src.relative_to(repo)
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, dst)
        if src.suffix != ".md":
            continue
        for m in LINK.finditer(src.read_text(encoding="utf-8")):
            target = m.group(1) or m.group(2)
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                continue
            path = target.split("#", 1)[0]
            resolved = (src.parent / path).resolve()
            if repo not in resolved.parents and resolved != repo:
                broken.append(f"{src.relative_to(repo)}: {target} leaves the repository")
            elif not resolved.exists():
                broken.append(f"{src.relative_to(repo)}: {target} does not exist")
            elif resolved.is_dir():
                broken.append(f"{src.relative_to(repo)}: {target} is a directory (link a file)")
            else:
                todo.append(resolved)
    for line in broken:
        print(f"scripts/docs: broken link in {line}", file=sys.stderr)
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
