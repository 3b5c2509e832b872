#!/usr/bin/env python3
"""Layout checks for the host code (issue 36); standard library only, reads sources as text.

Usage: python3 scripts/check_layout.py [--root DIR] [--max-function-lines N] [--functions-in DIR]...
                                      [--only cycles|functions|names]...

Checks, each printed as a section with one finding a line:

cycles     Include cycles between folders of host/. Every .hpp/.cpp/.cu/.cuh/.h under host/ is read for
           its #include "..." and #include <...> lines (comments skipped). Each is resolved to a file
           under host/: quoted ones first against the including file's folder, then both kinds against
           the include roots host/, host/include/ (<spreadmap/...>), host/render/include/ and
           host/cuda/include/ (and the repository root, for "host/..." paths). Includes that resolve to
           nothing under host/ (standard, third-party, plugins) are left out. Each file stands for its
           folder relative to host/ (e.g. workflow/map, engine; "." for host/ itself); folder A -> B when
           a file in A includes one in B. Tarjan's algorithm gives the strongly connected components;
           each with more than one folder is a cycle, printed with its folders, one shortest loop
           through them, and for every edge inside it one include line (file:line -> included file)
           and how many lines make that edge.
functions  Functions over N lines (default 80) under host/workflow/. A scanner blanks comments, string
           and char literals (raw strings R"d(...)d" included; digit separators 1'000 are not char
           literals) and preprocessor lines, then matches braces. At namespace and class scope a "{"
           opens a function body when it follows a parameter list ")" and only what may stand there
           (const, noexcept(...), override, final, &, &&, -> return type, requires ..., a constructor's
           member initializer list); a lambda assigned to a namespace-scope variable counts as a
           function of that name. Everything in a body (lambdas, local classes) counts towards the
           function. Both sides of an #if are read, so each should balance its braces (a file that
           does not is named in a warning on stderr). Length = lines from the function's name to its closing brace, both counted.
           Printed as file:line name length (a method as Class::name), longest first.
           --functions-in DIR (repeatable) measures other folders instead, e.g. host/render.
names      Duplicate names across folders: source files of one file name (stem and extension) in
           different folders of host/ and plugins/; and types (class/struct/union/enum, with a body:
           the name followed by "{", ":" or "final"; forward declarations and specialisations
           X<...> are left out) declared at namespace scope under one name in different folders of
           host/. Each location shows its namespace, "(anonymous)" for an unnamed one.

prefix     The "error: " before a message is written in one place, host/core/error.cpp (printed()): a
           string literal in code (comments aside) anywhere else under host/ that starts with it is
           printed as file:line.

The last line is the summary `layout: N include cycles, M functions over 80 lines, K duplicate file
names, L duplicate type names, P error prefixes` (only the checks run); the exit status is 1 when there is any finding,
0 when there is none, 2 for bad arguments.
"""

import argparse
import bisect
import collections
import os
import re
import sys
from pathlib import Path

SOURCE_EXTS = {".hpp", ".cpp", ".cu", ".cuh", ".h"}
INCLUDE_ROOTS = ["host", "host/include", "host/render/include", "host/cuda/include", "."]
INCLUDE_RE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*([<"])([^>"\n]+)[>"]', re.M)
RAW_PREFIXES = {"R", "u8R", "uR", "UR", "LR"}


# ---------------------------------------------------------------------------------------------- lexing

def blank(text, strings=True, directives=True):
    """The text with comments blanked (and, if asked, the insides of string and char literals and
    whole preprocessor lines), newlines kept so that offsets and line numbers stay the same."""
    out = list(text)
    n = len(text)
    i = 0
    line_start = True  # only whitespace since the last newline
    in_dir = False  # inside a preprocessor directive

    def wipe(a, b):  # blank text[a:b], keeping newlines
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        nxt = text[i + 1] if i + 1 < n else ""
        if c == "\n":
            if in_dir and not text[:i].rstrip("\r").endswith("\\"):
                in_dir = False
            line_start = True
            i += 1
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        if c == "/" and nxt == "/":
            end = text.find("\n", i)
            end = n if end < 0 else end
            wipe(i, end)
            i = end
            continue
        if c == "/" and nxt == "*":
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            wipe(i, end)
            i = end
            continue
        if line_start and c == "#" and directives:
            in_dir = True
        line_start = False
        if c in "\"'":
            j = i  # the identifier or number this quote follows
            while j > 0 and (text[j - 1].isalnum() or text[j - 1] in "_."):
                j -= 1
            if c == "'" and j < i and text[j].isdigit():  # a digit separator: 1'000'000
                if in_dir:
                    out[i] = " "
                i += 1
                continue
            if c == '"' and text[j:i] in RAW_PREFIXES:
                paren = text.find("(", i + 1)
                delim = text[i + 1:paren] if paren >= 0 else ""
                close = text.find(")" + delim + '"', paren + 1) if paren >= 0 else -1
                last = n - 1 if close < 0 else close + len(delim) + 1  # the closing quote
            else:
                last = i + 1
                while last < n and text[last] != c and text[last] != "\n":
                    last += 2 if text[last] == "\\" else 1
                last = min(last, n - 1)
            if strings:
                wipe(i + 1, last)
            if in_dir:
                wipe(i, last + 1)
            i = last + 1
            continue
        if in_dir:
            out[i] = " "
        i += 1
    return "".join(out)


TOKEN_RE = re.compile(
    r"""[A-Za-z_]\w*|\d[\w.']*|"[^"]*"|'[^']*'|::|->|\.\.\.|==|!=|<=|>=|\+=|-=|\*=|/=|%=|&=|\|=|\^=|&&|\|\||\S""")


class Tok:
    __slots__ = ("text", "line", "end")  # end: for a group, the index of the token after its closer

    def __init__(self, text, line, end=None):
        self.text, self.line, self.end = text, line, end

    def __repr__(self):
        return f"Tok({self.text!r}@{self.line})"


def tokenize(code):
    newlines = [m.start() for m in re.finditer("\n", code)]
    return [Tok(m.group(), bisect.bisect_right(newlines, m.start()) + 1) for m in TOKEN_RE.finditer(code)]


# --------------------------------------------------------------------------------------------- parsing

OPEN = {"(": ")", "[": "]", "{": "}"}
CLOSE = {")", "]", "}"}
TRAILER_WORDS = {"const", "volatile", "override", "final", "mutable", "constexpr", "consteval", "try", "&", "&&"}
NOT_NAMES = {"if", "for", "while", "switch", "return", "sizeof", "alignof", "decltype", "alignas", "noexcept",
             "requires", "static_assert", "throw", "catch", "new", "delete", "typeid", "co_return"}


def is_ident(t):
    return t[:1].isalpha() or t[:1] == "_"


def is_group(t, opener):
    return t.end is not None and t.text == opener


class Parser:
    """Walks the tokens of one file, recording functions (at namespace and class scope) and types
    (at namespace scope) as it goes."""

    def __init__(self, toks):
        self.toks = toks
        self.functions = []  # (name, first line, last line)
        self.types = []  # (name, line, namespace)

    def match(self, i):
        """Index after the bracket that closes the one at i."""
        depth = 0
        for k in range(i, len(self.toks)):
            t = self.toks[k].text
            if t in OPEN:
                depth += 1
            elif t in CLOSE:
                depth -= 1
                if depth == 0:
                    return k + 1
        return len(self.toks)

    def run(self):
        i = 0
        while i < len(self.toks):  # a stray "}" at file scope ends parse_scope: go on after it
            i = self.parse_scope(i, "top", [], [])

    def parse_scope(self, i, kind, ns, cls):
        """Parses from toks[i] to the '}' that closes this scope; kind is top, namespace, linkage or
        class; ns the enclosing namespaces, cls the enclosing classes (names a method Class::name)."""
        header = []
        toks = self.toks
        while i < len(toks):
            t = toks[i]
            if t.text == ";":
                header = []
                i += 1
            elif t.text == "}":
                return i + 1
            elif t.text in ("(", "["):
                j = self.match(i)
                header.append(Tok(t.text + OPEN[t.text], t.line, j))
                i = j
            elif t.text in (")", "]"):
                i += 1
            elif t.text == ":" and kind == "class" and len(header) == 1 and \
                    header[0].text in ("public", "private", "protected"):
                header = []
                i += 1
            elif t.text == "{":
                what = classify(header)
                if what[0] == "namespace":
                    i = self.parse_scope(i + 1, "namespace", ns + [what[1]], cls)
                    header = []
                elif what[0] == "linkage":
                    i = self.parse_scope(i + 1, "linkage", ns, cls)
                    header = []
                elif what[0] in ("class", "enum"):
                    name = type_name(what[1])
                    if name and kind != "class":
                        self.types.append((name[0], name[1], "::".join(ns)))
                    if what[0] == "class":
                        i = self.parse_scope(i + 1, "class", ns, cls + [name[0] if name else "(unnamed)"])
                    else:
                        i = self.match(i)
                    header = []
                elif what[0] == "function":
                    j = self.match(i)
                    self.functions.append(("::".join(cls + [what[1]]), what[2], toks[j - 1].line))
                    i = j
                    header = []
                else:  # an initializer, a member initializer's braces, an enum body...: part of the header
                    j = self.match(i)
                    header.append(Tok("{}", t.line, j))
                    i = j
            else:
                header.append(t)
                i += 1
        return i


def strip_template(h):
    """h without leading template<...> heads, attributes and export."""
    k = 0
    while k < len(h):
        if h[k].text == "template" and k + 1 < len(h) and h[k + 1].text == "<":
            depth = 0
            k += 1
            while k < len(h):
                if h[k].text == "<":
                    depth += 1
                elif h[k].text == ">":
                    depth -= 1
                    if depth == 0:
                        break
                k += 1
            k += 1
        elif is_group(h[k], "[]") or h[k].text in ("export", "typedef"):
            k += 1
        else:
            break
    return h[k:]


def top_level_assign(h):
    """Index of a top-level '=' that is not part of an operator's name, or None."""
    for k, t in enumerate(h):
        if t.text == "=" and not (k > 0 and h[k - 1].text == "operator"):
            return k
    return None


def classify(header):
    """What a '{' after these header tokens opens: ('namespace', name), ('linkage',), ('class', head),
    ('enum', head), ('function', name, line) or ('other',)."""
    h = strip_template(header)
    if not h:
        return ("other",)
    first = h[0].text
    if first == "namespace" or (first == "inline" and len(h) > 1 and h[1].text == "namespace"):
        names = [t.text for t in h if t.text not in ("inline", "namespace")]
        return ("namespace", "".join(names) or "(anonymous)")
    if first == "extern" and len(h) == 2 and h[1].text.startswith('"'):
        return ("linkage",)
    eq = top_level_assign(h)
    if first in ("class", "struct", "union", "enum"):
        if eq is not None:
            return ("other",)
        return ("enum" if first == "enum" else "class", h[1:])
    if eq is not None:
        return lambda_initializer(h, eq)
    for k, t in enumerate(h):
        if not is_group(t, "()"):
            continue
        name = function_name(h, k)
        if name is None:
            continue
        state = trailer(h[k + 1:])
        if state == "body":
            return ("function", name[0], name[1])
        if state == "init-brace":
            return ("other",)
    return ("other",)


def lambda_initializer(h, eq):
    """A namespace-scope `auto name = [..](..) specifiers {` is a function called name."""
    rest = h[eq + 1:]
    for k, t in enumerate(rest):
        if is_group(t, "[]"):
            after = rest[k + 1:]
            if after and is_group(after[0], "()"):
                after = after[1:]
            if trailer(after) == "body" and eq > 0 and is_ident(h[eq - 1].text):
                return ("function", h[eq - 1].text + " (lambda)", h[eq - 1].line)
            break
    return ("other",)


def function_name(h, k):
    """(name, line) of the function whose parameter list is h[k], or None when h[k] is not one."""
    if k == 0:
        return None
    # operator forms: operator==, operator(), operator[], operator bool, operator new[]...
    for back in range(1, min(k, 5) + 1):
        if h[k - back].text == "operator":
            name = "operator" + "".join(t.text if t.end is None else t.text for t in h[k - back + 1:k])
            start = k - back
            return (qualify(h, start, name), h[start].line)
    j = k - 1
    if h[j].text == ">":  # template arguments on the name: f<int>(...)
        j = skip_angles_back(h, j)
        if j is None:
            return None
    if j < 0 or not is_ident(h[j].text) or h[j].text in NOT_NAMES:
        return None
    name = h[j].text
    if j > 0 and h[j - 1].text == "~":
        name = "~" + name
        j -= 1
    return (qualify(h, j, name), h[j].line)


def skip_angles_back(h, j):
    """From the '>' at j, the index of the token before its matching '<'; None if unmatched."""
    depth = 0
    while j >= 0:
        if h[j].text == ">":
            depth += 1
        elif h[j].text == "<":
            depth -= 1
            if depth == 0:
                return j - 1
        j -= 1
    return None


def qualify(h, j, name):
    """name, with the Scope:: qualifiers that stand before h[j]."""
    while j >= 2 and h[j - 1].text == "::":
        p = j - 2
        if h[p].text == ">":
            p = skip_angles_back(h, p)
            if p is None:
                break
        if p < 0 or not is_ident(h[p].text):
            break
        name = h[p].text + "::" + name
        j = p
    return name


def trailer(rest):
    """After a parameter list: 'body' when a '{' here opens the body, 'init-brace' when it opens a
    member initializer's braces, None when these tokens cannot follow a parameter list."""
    k = 0
    while k < len(rest):
        t = rest[k]
        if t.text in TRAILER_WORDS or is_group(t, "[]"):
            k += 1
        elif t.text in ("noexcept", "throw"):
            k += 2 if k + 1 < len(rest) and is_group(rest[k + 1], "()") else 1
        elif t.text in ("->", "requires"):
            return "body"
        elif t.text == ":":
            return init_list(rest[k + 1:])
        else:
            return None
    return "body"


def init_list(items):
    """A constructor's member initializer list: 'body' when complete, 'init-brace' when the last item
    still awaits its braces, None when it is not one."""
    k, n = 0, len(items)
    while True:
        angle = 0
        named = False
        while k < n:  # the member or base name, template arguments and all
            t = items[k]
            if t.text == "<":
                angle += 1
            elif t.text == ">":
                angle -= 1
            elif t.text == "," and angle > 0:
                pass
            elif is_ident(t.text) or t.text in ("::", "...") or (angle > 0 and t.end is None):
                named = True
            elif angle > 0 and t.end is not None:
                pass
            else:
                break
            k += 1
        if k == n:
            return "init-brace" if named else None
        if not named or not (is_group(items[k], "()") or is_group(items[k], "{}")):
            return None
        k += 1
        if k < n and items[k].text == "...":
            k += 1
        if k == n:
            return "body"
        if items[k].text != ",":
            return None
        k += 1


def type_name(head):
    """(name, line) of a class/struct/union/enum from the tokens after its keyword; None for an
    unnamed one or a specialisation X<...>."""
    k = 0
    if k < len(head) and head[k].text in ("class", "struct"):  # enum class / enum struct
        k += 1
    last = None
    while k < len(head):
        t = head[k]
        if t.text in (":", "final"):
            break
        if t.text == "<":
            return None
        if is_group(t, "()") or is_group(t, "[]"):
            k += 1
            continue
        if is_ident(t.text) and t.text != "alignas":
            last = k
        k += 1
    if last is None:
        return None
    return (qualify(head, last, head[last].text), head[last].line)


# ---------------------------------------------------------------------------------------------- checks

def source_files(base):
    if not base.is_dir():
        return []
    return sorted(p for p in base.rglob("*") if p.is_file() and p.suffix in SOURCE_EXTS)


def folder_of(host, path):
    rel = path.parent.relative_to(host).as_posix()
    return rel if rel else "."


def resolve_include(root, host, including, target, quoted):
    candidates = []
    if quoted:
        candidates.append(including.parent / target)
    candidates += [root / r / target for r in INCLUDE_ROOTS]
    for c in candidates:
        c = Path(os.path.normpath(c))
        if c.is_file() and c.suffix in SOURCE_EXTS and c.is_relative_to(host):
            return c
    return None


def tarjan(nodes, edges):
    """Strongly connected components (iterative Tarjan)."""
    index, low, on_stack, stack, comps = {}, {}, set(), [], []
    counter = 0
    for start in nodes:
        if start in index:
            continue
        work = [(start, iter(sorted(edges.get(start, ()))))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                    advanced = True
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                comps.append(sorted(comp))
    return comps


def shortest_loop(comp, edges):
    """One shortest closed walk through comp's first folder, as a list of folders."""
    members = set(comp)
    start = comp[0]
    prev = {start: None}
    queue = collections.deque([start])
    while queue:
        v = queue.popleft()
        for w in sorted(edges.get(v, ())):
            if w not in members:
                continue
            if w == start:
                path = [v]
                while prev[path[-1]] is not None:
                    path.append(prev[path[-1]])
                return list(reversed(path)) + [start]
            if w not in prev:
                prev[w] = v
                queue.append(w)
    return [start]


def check_cycles(root):
    host = root / "host"
    edges = collections.defaultdict(set)
    examples = collections.defaultdict(list)  # (A, B) -> [(file, line, included)]
    folders = set()
    for f in source_files(host):
        a = folder_of(host, f)
        folders.add(a)
        text = blank(f.read_text(errors="replace"), strings=False, directives=False)
        for m in INCLUDE_RE.finditer(text):
            target = resolve_include(root, host, f, m.group(2).strip(), m.group(1) == '"')
            if target is None:
                continue
            b = folder_of(host, target)
            if a != b:
                edges[a].add(b)
                line = text.count("\n", 0, m.start()) + 1
                examples[(a, b)].append((f.relative_to(root).as_posix(), line, target.relative_to(root).as_posix()))
    comps = [c for c in tarjan(sorted(folders), edges) if len(c) > 1]
    comps.sort(key=lambda c: (-len(c), c))
    lines = []
    for n, comp in enumerate(comps, 1):
        lines.append(f"cycle {n}: {len(comp)} folders: {', '.join(comp)}")
        lines.append(f"  loop: {' -> '.join(shortest_loop(comp, edges))}")
        for a in comp:
            for b in sorted(edges[a]):
                if b in comp:
                    ex = sorted(examples[(a, b)])
                    f, line, inc = ex[0]
                    more = f" (+{len(ex) - 1} more include lines)" if len(ex) > 1 else ""
                    lines.append(f"  {a} -> {b}: {f}:{line} -> {inc}{more}")
    return len(comps), lines


def parse_file(path):
    toks = tokenize(blank(path.read_text(errors="replace")))
    opened = sum(t.text == "{" for t in toks)
    closed = sum(t.text == "}" for t in toks)
    if opened != closed:  # e.g. #if / #else branches that each open a brace: both are read
        print(f"check_layout: warning: {path}: {opened} '{{' but {closed} '}}'; its functions and types may be "
              "misread", file=sys.stderr)
    parser = Parser(toks)
    parser.run()
    return parser


def check_functions(root, max_lines, folders):
    found = []
    files = sorted({f for d in folders for f in source_files(root / d)})
    for f in files:
        for name, first, last in parse_file(f).functions:
            length = last - first + 1
            if length > max_lines:
                found.append((length, f.relative_to(root).as_posix(), first, name))
    found.sort(key=lambda x: (-x[0], x[1], x[2]))
    return len(found), [f"{f}:{line} {name} {length} lines" for length, f, line, name in found]


def check_names(root):
    host = root / "host"
    by_file = collections.defaultdict(set)
    for base in (host, root / "plugins"):
        for f in source_files(base):
            by_file[f.name].add(f.parent.relative_to(root).as_posix())
    file_lines = [f"file {name}: {', '.join(sorted(dirs))}" for name, dirs in sorted(by_file.items()) if len(dirs) > 1]

    by_type = collections.defaultdict(list)  # name -> [(folder, file, line, namespace)]
    for f in source_files(host):
        for name, line, ns in parse_file(f).types:
            by_type[name].append((folder_of(host, f), f.relative_to(root).as_posix(), line, ns))
    type_lines = []
    for name, places in sorted(by_type.items()):
        if len({p[0] for p in places}) < 2:
            continue
        where = "; ".join(f"{folder} ({f}:{line} in {ns or '(global)'})" for folder, f, line, ns in sorted(places))
        type_lines.append(f"type {name}: {where}")
    return len(file_lines), len(type_lines), file_lines + type_lines


PREFIX_HOME = "host/core/error.cpp"
PREFIX_RE = re.compile(r'(?<![\\\w])"error: ')


def check_prefix(root):
    found = []
    for f in source_files(root / "host"):
        rel = f.relative_to(root).as_posix()
        if rel == PREFIX_HOME:
            continue
        code = blank(f.read_text(encoding="utf-8", errors="replace"), strings=False, directives=True)
        for m in PREFIX_RE.finditer(code):
            found.append(f"{rel}:{code.count(chr(10), 0, m.start()) + 1}")
    return len(found), found


def main(argv=None):
    ap = argparse.ArgumentParser(description="Layout checks for host/ (issue 36): include cycles between "
                                 "folders, long functions in host/workflow/, duplicate file and type names.")
    ap.add_argument("--root", type=Path, default=Path(__file__).resolve().parent.parent,
                    help="repository root (default: the one holding this script)")
    ap.add_argument("--max-function-lines", type=int, default=80, metavar="N",
                    help="longest a function in host/workflow/ may be (default 80)")
    ap.add_argument("--functions-in", action="append", metavar="DIR",
                    help="folder, relative to the root, whose functions are measured (repeatable; "
                    "default host/workflow)")
    ap.add_argument("--only", action="append", choices=["cycles", "functions", "names", "prefix"],
                    help="run only this check (repeatable)")
    args = ap.parse_args(argv)
    root = args.root.resolve()
    if not (root / "host").is_dir():
        ap.error(f"{root} has no host/ folder")
    only = set(args.only or ["cycles", "functions", "names", "prefix"])
    summary = []
    total = 0
    if "cycles" in only:
        n, lines = check_cycles(root)
        print(f"== include cycles between folders of host/ ({n})")
        print("\n".join(lines) if lines else "none")
        summary.append(f"{n} include cycles")
        total += n
    if "functions" in only:
        dirs = args.functions_in or ["host/workflow"]
        n, lines = check_functions(root, args.max_function_lines, dirs)
        where = ", ".join(d.rstrip("/") + "/" for d in dirs)
        print(f"== functions over {args.max_function_lines} lines in {where} ({n})")
        print("\n".join(lines) if lines else "none")
        summary.append(f"{n} functions over {args.max_function_lines} lines")
        total += n
    if "names" in only:
        nf, nt, lines = check_names(root)
        print(f"== duplicate names across folders ({nf} file names in host/ and plugins/, {nt} type names in host/)")
        print("\n".join(lines) if lines else "none")
        summary.append(f"{nf} duplicate file names, {nt} duplicate type names")
        total += nf + nt
    if "prefix" in only:
        n, lines = check_prefix(root)
        print(f"== \"error: \" written outside {PREFIX_HOME} ({n})")
        print("\n".join(lines) if lines else "none")
        summary.append(f"{n} error prefixes")
        total += n
    print("layout: " + ", ".join(summary))
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main())
