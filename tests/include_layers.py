#!/usr/bin/env python3
"""No include runs upward (#71): every #include in libradiosity/src/<folder>/ names a header of
its own folder or of a folder listed before it in libradiosity/layers.txt (bottom up). Also fails for a folder the
list leaves out and for a public header with no folder. Usage: include_layers.py LIBRADIOSITY"""
import os
import re
import sys

root = sys.argv[1]
src, public = os.path.join(root, "src"), os.path.join(root, "include", "radiosity")
order, named = [], {}
for line in open(os.path.join(root, "layers.txt")):
    words = line.split("#")[0].split()
    if len(words) == 1:
        order.append(words[0])
    elif len(words) == 3 and words[0] == "header":
        named[words[1]] = words[2]
    elif words:
        sys.exit("layers.txt: cannot read '%s'" % line.strip())
rank = {folder: k for k, folder in enumerate(order)}
problems = []
folders = sorted(d for d in os.listdir(src) if os.path.isdir(os.path.join(src, d)))
for d in folders:
    if d not in rank:
        problems.append("libradiosity/src/%s/ is not in layers.txt: add it where it belongs" % d)
def files_of(d):
    """A folder's files, its sub-folders' too (mesh/ has its passes' families), by path."""
    for here, _, names in os.walk(os.path.join(src, d)):
        for name in sorted(names):
            yield os.path.relpath(os.path.join(here, name), os.path.join(src, d))

sources = {}
for d in folders:
    for f in files_of(d):
        if f.endswith(".cpp"):
            sources.setdefault(os.path.basename(f)[:-4], set()).add(d)
owner = {}
for h in sorted(os.listdir(public)):
    name = h.split(".")[0]
    if name in named:
        owner[name] = named[name]
    elif len(sources.get(name, ())) == 1:
        owner[name] = next(iter(sources[name]))
    else:
        problems.append("include/radiosity/%s has no folder: name it in layers.txt (header %s FOLDER)" % (h, name))
include = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
checked = 0
for d in folders:
    for f in sorted(files_of(d)):
        if not f.endswith((".cpp", ".hpp")):
            continue
        for number, line in enumerate(open(os.path.join(src, d, f)), 1):
            m = include.match(line)
            if not m:
                continue
            path = m.group(1)
            if path.startswith("radiosity/"):
                target = owner.get(path[len("radiosity/"):].split(".")[0])
            elif "/" in path and path.split("/")[0] in rank:
                target = path.split("/")[0]
            else:
                continue  # its own folder's, or another module's (radfmt/)
            checked += 1
            if target in rank and d in rank and rank[target] > rank[d]:
                problems.append("libradiosity/src/%s/%s:%d includes %s, of %s/, which layers.txt lists "
                                "after %s/: a lower stage may not use a higher one (move what both "
                                "need down)" % (d, f, number, path, target, d))
for p in problems:
    print(p)
print("%d includes checked across %d folders; %d problem(s)" % (checked, len(folders), len(problems)))
sys.exit(1 if problems else 0)
