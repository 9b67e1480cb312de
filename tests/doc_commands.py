#!/usr/bin/python3
"""The commands of README.md and docs/guide/*.md that write a solution file: the example programs (examples/contact,
examples/prism, examples/generic, examples/fclib, and examples/scene.py, examples/generic.py in Python) with -o FILE
(--out FILE), as the pages show them in code blocks and in `inline code`, backslash continuations joined, `&&` chains
split.

  tests/doc_commands.py          list them: page, then the command

tests/suite_converged.py runs each (its file renamed into tests/output/) and checks the file with
tests/check_solution.py law FILE --steps; tests/suite_package.py checks the pages' links (broken_links())."""
import glob
import os
import re
import shlex

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROGRAMS = ("examples/contact", "examples/prism", "examples/generic", "examples/fclib", "examples/scene.py", "examples/generic.py")
OUTPUT = ("-o", "--out")


def pages():
    return [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "guide", "*.md")))


def candidates(text):
    """Every piece of code of a markdown page: the lines of fenced and indented blocks, and the inline spans"""
    text = re.sub(r"\\\n\s*", " ", text)  # continuation lines
    found, prose, fenced = [], [], False
    for line in text.split("\n"):
        if line.strip().startswith("```"):
            fenced = not fenced
            prose.append("")
        elif fenced or re.match(r"^    \S", line):
            found.append(line)
            prose.append("")
        else:
            prose.append(line)
    found += [" ".join(span.split()) for span in re.findall(r"`([^`]+)`", "\n".join(prose))]
    return found


def command(piece):
    """The argv of a piece of code that runs an example and writes a file, else None"""
    piece = re.sub(r"\s#\s.*$", "", piece).strip()
    if "..." in piece or "$" in piece:
        return None
    try:
        argv = shlex.split(piece)
    except ValueError:
        return None
    start = 0
    if argv[:1] == ["mpiexec"] and len(argv) > 3 and argv[1] == "-n":
        start = 3
    if argv[start:start + 1] == ["/usr/bin/python3"]:
        start += 1
    if start >= len(argv) or argv[start] not in PROGRAMS:
        return None
    if not any(a in OUTPUT for a in argv[start + 1:-1] if a):
        return None
    return argv


def commands():
    """(page, argv) of every command that writes a file, in page order, each once"""
    seen, out = set(), []
    for page in pages():
        for piece in candidates(open(page).read()):
            for part in piece.split("&&"):
                argv = command(part)
                if argv and tuple(argv) not in seen:
                    seen.add(tuple(argv))
                    out.append((os.path.relpath(page, ROOT), argv))
    return out


def output_of(argv):
    """The index of the output file's argument"""
    return max(i for i, a in enumerate(argv[:-1]) if a in OUTPUT) + 1


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens"""
    text = re.sub(r"[`*]", "", heading.strip().lower())
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def broken_links():
    """(page, link) of every relative link of README.md, docs/guide/*.md and docs/options.md to a file that does not
    exist or a heading that the file does not have"""
    broken = []
    for page in pages() + [os.path.join(ROOT, "docs", "options.md")]:
        text = re.sub(r"```.*?```", "", open(page).read(), flags=re.S)
        for link in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", link):
                continue
            path, _, anchor = link.partition("#")
            target = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            if not os.path.exists(target):
                broken.append((os.path.relpath(page, ROOT), link))
            elif anchor and target.endswith(".md"):
                headings = re.findall(r"^#+\s+(.*)$", re.sub(r"```.*?```", "", open(target).read(), flags=re.S), re.M)
                if anchor not in {slug(h) for h in headings}:
                    broken.append((os.path.relpath(page, ROOT), link))
    return broken


if __name__ == "__main__":
    for page, argv in commands():
        print("%-36s %s" % (page, " ".join(shlex.quote(a) for a in argv)))
    for page, link in broken_links():
        print("%-36s broken link %s" % (page, link))
