#!/usr/bin/env bash
# No function in src/ or reference/ longer than a screenful or two (docs/STYLE: "functions short
# enough to see whole"). Scans every .h/.hpp/.cpp with its comments, string and character literals
# and preprocessor lines removed, matching braces: a function is a brace block opened after a
# parameter list at namespace or class scope (free functions, member functions defined inside
# their class, constructors with initializer lists, signatures over several lines) or a lambda
# assigned at namespace or class scope; lambdas and blocks inside a function count towards it.
# A function's length runs from the first line of its signature to its closing brace. Prints
# each one over the limit as file:line: function (N lines) and exits 1 when there is one.
# Run by ctest (FunctionLength).
#   scripts/check-function-length.sh [ROOT] [LIMIT]     (default: the repository, 100)
set -euo pipefail
root=${1:-$(dirname "$0")/..}
limit=${2:-100}
cd "$root"

python3 - "$limit" src reference <<'PYTHON'
import os
import re
import sys

limit = int(sys.argv[1])
roots = sys.argv[2:]

IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
LITERAL_PREFIXES = {"u8", "u", "U", "L", "R", "u8R", "uR", "UR", "LR"}
# Merged so that "operator==" or "a <= b" hold no "=" of their own; ">>" stays two tokens (it
# closes two template argument lists).
TWO_CHAR = {"::", "->", "==", "!=", "<=", ">=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^="}


def tokens(text):
    """(token, line) pairs of the code: no comments, literals or preprocessor lines. A string or
    character literal becomes the token '""'."""
    i, line, n = 0, 1, len(text)
    at_line_start = True
    out = []
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
            at_line_start = True
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        if c == "#" and at_line_start:  # a preprocessor line, with its continuations
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    line += 1
                    i += 1
                i += 1
            continue
        at_line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            line += text.count("\n", i, end)
            i = end
            continue
        if c.isdigit() or (c == "." and i + 1 < n and text[i + 1].isdigit()):
            j = i + 1
            while j < n and (text[j].isalnum() or text[j] in "_.'" or
                             (text[j] in "+-" and text[j - 1] in "eEpP")):
                j += 1
            out.append(("0", line))
            i = j
            continue
        m = IDENT.match(text, i)
        if m:
            word = m.group(0)
            j = m.end()
            if word in LITERAL_PREFIXES and j < n and text[j] in "\"'":
                if word.endswith("R") and text[j] == '"':  # raw string R"delim( ... )delim"
                    open_paren = text.index("(", j)
                    closing = ")" + text[j + 1:open_paren] + '"'
                    end = text.index(closing, open_paren) + len(closing)
                    out.append(('""', line))
                    line += text.count("\n", i, end)
                    i = end
                    continue
                i = j  # the literal follows
                continue
            out.append((word, line))
            i = j
            continue
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                if text[j] == "\\":
                    j += 1
                j += 1
            out.append(('""', line))
            line += text.count("\n", i, j)
            i = j + 1
            continue
        if text[i:i + 2] in TWO_CHAR:
            out.append((text[i:i + 2], line))
            i += 2
            continue
        out.append((c, line))
        i += 1
    return out


def strip_template(head):
    """The head without leading `template <...>` clauses."""
    while len(head) >= 2 and head[0][0] == "template" and head[1][0] == "<":
        depth, k = 0, 1
        while k < len(head):
            t = head[k][0]
            depth += (t == "<") - (t == ">")
            if t in "([":
                depth += 100  # a parenthesised expression: its < and > are no brackets
            if t in ")]":
                depth -= 100
            k += 1
            if depth == 0:
                break
        head = head[k:]
    return head


def top_level(head):
    """Indices of the head's tokens that lie outside any (), [] or {}."""
    depth, result = 0, []
    for k, (t, _) in enumerate(head):
        if t in "([{":
            depth += 1
        elif t in ")]}":
            depth -= 1
        elif depth == 0:
            result.append(k)
    return result


def function_name(head, paren):
    """The (qualified) name before the parameter list at head[paren]."""
    words = [t for t, _ in head[:paren]]
    if "operator" in words:
        k = len(words) - 1 - words[::-1].index("operator")
        return "".join(words[k - 2:k] if k >= 2 and words[k - 1] == "::" else []) + \
            "operator" + "".join(words[k + 1:])
    name = []
    k = len(words) - 1
    while k >= 0:
        if IDENT.fullmatch(words[k]) or words[k] == "~":
            name.insert(0, words[k])
        elif words[k] == "::" or words[k] == ">":
            if words[k] == ">":  # Foo<T>::bar: skip the template arguments
                depth = 0
                while k >= 0:
                    depth += (words[k] == ">") - (words[k] == "<")
                    if depth == 0:
                        break
                    k -= 1
                k -= 1
                continue
            name.insert(0, "::")
        else:
            break
        if IDENT.fullmatch(words[k]) and k > 0 and words[k - 1] not in ("::", "~"):
            break
        k -= 1
    return "".join(name) or "(unnamed)"


def classify(head):
    """What a brace opened at namespace or class scope after `head` opens: ("scope",),
    ("class",), ("data",), ("function", name) or ("init",) (a member's brace initializer inside a
    constructor's initializer list, which continues the head)."""
    head = strip_template(head)
    if not head:
        return ("data",)
    words = [t for t, _ in head]
    if words[0] in ("namespace", "inline") and "namespace" in words[:2]:
        return ("scope",)
    if words[0] == "extern" and len(words) <= 2:
        return ("scope",)
    top = top_level(head)
    if words[0] in ("class", "struct", "union") or (words[0] == "typedef" and len(words) > 1 and
                                                     words[1] in ("class", "struct", "union")):
        return ("class",)
    if words[0] == "enum":
        return ("data",)
    # An unclosed "(": a brace in a default argument or an initializer list's argument.
    if sum((t == "(") - (t == ")") for t in words) > 0:
        return ("init",)
    assignments = [k for k in top if words[k] == "=" and (k == 0 or words[k - 1] != "operator")]
    if assignments:
        k = assignments[0]
        if k + 1 < len(words) and words[k + 1] == "[":
            name = words[k - 1] if k > 0 and IDENT.fullmatch(words[k - 1]) else "(lambda)"
            return ("function", name)
        return ("data",)
    # The parameter list: the first top-level "(" (its tokens are not top-level themselves, so
    # look for the "(" that opens a group at depth 0).
    depth, paren = 0, None
    for k, t in enumerate(words):
        if t == "(" and depth == 0 and paren is None:
            if k > 0 and words[k - 1] in ("alignas", "decltype", "__attribute__", "__declspec"):
                pass
            elif k > 0 and words[k - 1] == "operator":
                pass  # operator(): the parameter list is the next group
            else:
                paren = k
        if t in "([{":
            depth += 1
        elif t in ")]}":
            depth -= 1
    if paren is None:
        return ("data",)
    # A constructor's initializer list: ") : member(...), member{...}" — a brace after a member's
    # name is that member's initializer, not the body.
    closing = None
    depth = 0
    for k in range(paren, len(words)):
        depth += words[k] in "([{"
        depth -= words[k] in ")]}"
        if depth == 0:
            closing = k
            break
    if closing is not None and ":" in words[closing + 1:]:
        if IDENT.fullmatch(words[-1]) or words[-1] == ">":
            return ("init",)
    return ("function", function_name(head, paren))


def long_functions(path, text):
    toks = tokens(text)
    found = []
    # Stack of scopes: "scope" (namespace), "class", "data", "function", "init".
    stack = []
    head = []
    function = None  # (name, first line, depth) of the function being read
    for t, line in toks:
        inside = function is not None
        if t == "{":
            if inside:
                stack.append("block")
                continue
            if stack and stack[-1] in ("data", "init"):
                stack.append("data")
                continue
            kind = classify(head)
            if kind[0] == "function":
                function = (kind[1], head[0][1] if head else line, len(stack))
                stack.append("function")
                head = []
            elif kind[0] == "init":
                stack.append("init")
            else:
                stack.append(kind[0])
                head = []
            continue
        if t == "}":
            kind = stack.pop() if stack else "scope"
            if inside and len(stack) == function[2]:
                name, first, _ = function
                length = line - first + 1
                if length > limit:
                    found.append((path, first, name, length))
                function = None
                head = []
            elif kind == "init":
                head.append(("{}", line))  # the initializer stays part of the head
            elif not inside and not (stack and stack[-1] in ("data", "init")):
                head = []
            continue
        if inside or (stack and stack[-1] in ("data", "init")):
            continue
        if t == ";":
            head = []
            continue
        if t == ":" and len(head) == 1 and head[0][0] in ("public", "private", "protected"):
            head = []
            continue
        head.append((t, line))
    return found


def sources():
    for root in roots:
        for folder, dirs, files in os.walk(root):
            dirs.sort()
            for name in sorted(files):
                if name.endswith((".h", ".hpp", ".cpp")):
                    yield os.path.join(folder, name)


violations = []
for path in sources():
    with open(path, encoding="utf-8", errors="replace") as f:
        violations += long_functions(path, f.read())
for path, line, name, length in violations:
    print(f"{path}:{line}: {name} is {length} lines, over the limit of {limit}")
if violations:
    print(f"{len(violations)} function(s) over {limit} lines: split them into named steps",
          file=sys.stderr)
    sys.exit(1)
PYTHON
