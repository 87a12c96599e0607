#!/usr/bin/env python3
"""Fails if a header in src/ declares a public function without \\pre or \\throw in its doc comment.

Parses every header with clang (-fparse-all-comments, JSON AST filtered to namespace quadcover), so what counts as a
declaration and as its doc comment is the compiler's. Checked: free functions, public member functions and
constructors with parameters (not copy/move), in src/, not in a `detail` namespace, not defaulted/deleted, not
operators or destructors; overrides inherit their base's contract. `--pending HEADER` lists a header's missing
contracts without failing (for a header another branch is rewriting). Exit 0 if none is missing, 1 otherwise, 2 if
clang cannot parse the headers.
Usage: check_contracts.py [--clang clang++] [--pending src/x/y.h]... SRC_DIR [-- extra clang flags]
"""
import json
import os
import subprocess
import sys
import tempfile

TAGS = {"pre", "throw", "throws", "exception"}
FUNCS = {"FunctionDecl", "CXXMethodDecl", "CXXConstructorDecl", "CXXConversionDecl"}


def comment_tags(node):
    tags = set()
    stack = [node]
    while stack:
        n = stack.pop()
        if n.get("kind") == "BlockCommandComment":
            tags.add(n.get("name"))
        stack.extend(n.get("inner", []))
    return tags


class Walker:
    def __init__(self, src_dir):
        self.src = os.path.realpath(src_dir)
        self.file = None
        self.line = None
        self.missing = {}  # (file, line) -> name
        self.seen = set()
        self.sources = {}

    def _loc(self, loc):
        if not loc:
            return
        if "spellingLoc" in loc:  # macro: the expansion is where the text is
            self._loc(loc.get("spellingLoc"))
            self._loc(loc.get("expansionLoc"))
            return
        if "file" in loc:
            self.file = loc["file"]
        if "line" in loc:
            self.line = loc["line"]

    def in_src(self, f):
        if f is None:
            return False
        p = os.path.realpath(f)
        return p.startswith(self.src + os.sep) and p.endswith(".h")

    def walk(self, node, scope):
        # Locations are printed incrementally (file/line omitted when unchanged): follow them in print order.
        self._loc(node.get("loc"))
        where = (self.file, self.line)
        rng = node.get("range", {})
        self._loc(rng.get("begin"))
        first = self.line
        self._loc(rng.get("end"))
        node["_lines"] = (first, self.line)
        kind = node.get("kind", "")
        name = node.get("name", "")
        access = node.get("access", "public")
        if kind == "NamespaceDecl" and (name == "detail" or name == ""):
            return self._skip(node)
        if kind in ("CXXRecordDecl", "ClassTemplateDecl") or kind == "NamespaceDecl":
            if access != "public" or node.get("isImplicit"):
                return self._skip(node)
            inner_scope = scope + [(name, node.get("tagUsed"))]
            current = "private" if node.get("tagUsed") == "class" else "public"
            for c in node.get("inner", []):
                if c.get("kind") == "AccessSpecDecl":
                    current = c.get("access", current)
                if kind != "NamespaceDecl" and c.get("kind") != "AccessSpecDecl":
                    c["access"] = current
                self.walk(c, inner_scope)
            return
        if kind == "FunctionTemplateDecl":
            if access == "public":
                for c in node.get("inner", []):
                    if c.get("kind") in FUNCS:
                        c.setdefault("_template_comment", [x for x in node.get("inner", []) if x.get("kind") == "FullComment"])
            for c in node.get("inner", []):
                if c.get("kind") in FUNCS:
                    c["access"] = access
                self.walk(c, scope)
            return
        if kind in FUNCS:
            self.check(node, where, scope, access)
        self._skip(node, walk_children=True)

    def _skip(self, node, walk_children=False):
        # Still consume the locations of the subtree so the incremental file/line stay right.
        for c in node.get("inner", []):
            if walk_children and c.get("kind") in FUNCS | {"FunctionTemplateDecl", "CXXRecordDecl"}:
                self.walk(c, [])
            else:
                self._loc(c.get("loc"))
                r = c.get("range", {})
                self._loc(r.get("begin"))
                self._loc(r.get("end"))
                self._skip(c)

    def trailing_tag(self, path, first, last):
        # clang attaches ///< only to fields and variables; doxygen also to functions: accept it on the decl's lines.
        if path not in self.sources:
            with open(path, encoding="utf-8") as f:
                self.sources[path] = f.read().split("\n")
        for line in self.sources[path][first - 1:last]:
            if "///<" in line and any("\\" + t in line.split("///<", 1)[1] for t in TAGS):
                return True
        return False

    def check(self, node, where, scope, access):
        if access != "public" or node.get("isImplicit") or not self.in_src(where[0]):
            return
        name = node.get("name", "")
        if name.startswith("operator") or name.startswith("~"):
            return
        if node.get("explicitlyDefaulted") or node.get("explicitlyDeleted") or node.get("previousDecl"):
            return  # defaulted, deleted, or an out-of-line definition of a declaration checked where it is declared
        if any(c.get("kind") in ("OverrideAttr", "FinalAttr") for c in node.get("inner", [])):
            return  # an override has its base's contract
        params = [c for c in node.get("inner", []) if c.get("kind") == "ParmVarDecl"]
        if node["kind"] == "CXXConstructorDecl":
            if not params:
                return
            t = params[0].get("type", {}).get("qualType", "")
            if len(params) == 1 and (t.endswith("&&") or (t.startswith("const ") and t.endswith("&") and scope and t[6:-2].strip().split("<")[0].endswith(scope[-1][0]))):
                return  # copy/move
        comments = [c for c in node.get("inner", []) if c.get("kind") == "FullComment"] + node.get("_template_comment", [])
        tags = set()
        for c in comments:
            tags |= comment_tags(c)
        key = (os.path.relpath(os.path.realpath(where[0]), os.path.dirname(self.src)), where[1])
        if key in self.seen:
            return
        self.seen.add(key)
        if not tags & TAGS and not self.trailing_tag(where[0], *node["_lines"]):
            qual = "::".join(s[0] for s in scope if s[0] and s[0] != "quadcover")
            self.missing[key] = (qual + "::" if qual else "") + name


def main(argv):
    clang = "clang++"
    pending = set()
    extra = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1:]
    args = []
    it = iter(argv)
    for a in it:
        if a == "--clang":
            clang = next(it)
        elif a == "--pending":
            pending.add(os.path.normpath(next(it)))
        else:
            args.append(a)
    if len(args) != 1:
        print(__doc__)
        return 2
    src = args[0]
    headers = []
    for root, _, files in os.walk(src):
        headers += [os.path.join(root, f) for f in files if f.endswith(".h")]
    headers.sort()
    with tempfile.NamedTemporaryFile("w", suffix=".cpp", delete=False) as tu:
        for h in headers:
            tu.write('#include "%s"\n' % os.path.realpath(h))
    try:
        out = subprocess.run([clang, "-std=c++20", "-fsyntax-only", "-fparse-all-comments", "-I" + src,
                              "-Xclang", "-ast-dump=json", "-Xclang", "-ast-dump-filter=quadcover", *extra, tu.name],
                             capture_output=True, text=True)
    finally:
        os.unlink(tu.name)
    if out.returncode != 0:
        print(out.stderr[-4000:], file=sys.stderr)
        print("check_contracts: clang could not parse the headers", file=sys.stderr)
        return 2
    text = out.stdout
    dec = json.JSONDecoder()
    pos = 0
    w = Walker(src)
    while True:
        pos = text.find("{", pos)
        if pos < 0:
            break
        node, pos = dec.raw_decode(text, pos)
        w.file = w.line = None
        w.walk(node, [])
    failing = 0
    for (f, line), name in sorted(w.missing.items()):
        late = os.path.normpath(f) in pending
        failing += not late
        print("%s:%s: %s has no \\pre or \\throw in its doc comment%s" % (f, line, name, " (pending)" if late else ""))
    print("check_contracts: %d public functions checked, %d without a contract (%d pending)" %
          (len(w.seen), len(w.missing), len(w.missing) - failing))
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
