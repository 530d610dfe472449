#!/usr/bin/env python3
"""Doxygen INPUT_FILTER for mo2d's public headers (docs/api/Doxyfile.in).

The headers are written with plain `//` comments (the project's style); this filter shows them to
Doxygen as documentation, line for line (line numbers are kept, so warnings point at the header):

- the block after `#pragma once` (the file's maths) becomes the file's documentation (`@file`);
- a `//` block directly followed by a declaration (no blank line) at namespace or class scope
  becomes `///`, the documentation of that declaration, and of the declarations that follow it
  without a blank line or a comment of their own (a block above `potential_energy` and
  `damping_power` documents both);
- `T a = 0, b = 0;` is shown as `T a = 0; T b = 0;`, each with the comment of the line;
- a trailing `// text` after a declaration becomes `///< text`, and so do the `//` lines aligned
  under it that continue it;
- comments inside function bodies, and blocks followed by a blank line (section notes), stay plain.
Text outside backticks is escaped where Doxygen would read it as a command or an HTML tag.
"""
import re
import sys

COMMENT = re.compile(r"^(\s*)//\s?(.*)$")
TRAILING = re.compile(r"^(.*?\S.*?)(\s+)//\s?(.*)$")
SCOPE = re.compile(r"\b(namespace|struct|class|union|enum)\b")


ABBREVIATION = re.compile(r"\b(eq|e\.g|i\.e|ch|etc|vs|cf|Fig|Def|Prop|Ex)\. ")


def escape_plain(p):
    """Escape Doxygen commands and HTML-like tags (text outside code spans and quotes)."""
    p = p.replace("\\", "\\\\").replace("@", "\\@").replace("<", "\\<").replace(">", "\\>")
    p = p.replace("#", "\\#").replace("%", "\\%").replace("&", "\\&").replace("$", "\\$")
    return ABBREVIATION.sub(r"\1.\\ ", p)  # "eq. 5.27" does not end the brief description


def escape(text):
    """Escape text outside `code spans` and "quotes" (Doxygen reads both literally)."""
    text = text.replace("*/", "* /")
    parts = text.split("`")
    if len(parts) % 2 == 0:  # an unmatched backtick: leave it as text
        parts[-2] += "\\`" + parts.pop()
    for k in range(0, len(parts), 2):  # even parts are outside backticks
        quoted = parts[k].split('"')
        if len(quoted) % 2 == 1:  # balanced quotes: odd parts are quoted
            quoted = [q if j % 2 else escape_plain(q) for j, q in enumerate(quoted)]
            parts[k] = '"'.join(quoted)
        else:
            parts[k] = escape_plain(parts[k])
    return "`".join(parts)


def code_of(line):
    """The line without a trailing comment and without string literals."""
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split("//", 1)[0]


def doc_scope(stack):
    return all(kind == "decl" for kind in stack)


def braces(code, stack, pending_decl):
    """Update the brace stack with one line of code; returns whether a scope keyword is pending."""
    if SCOPE.search(code):
        pending_decl = True
    for ch in code:
        if ch == "{":
            stack.append("decl" if pending_decl else "body")
            pending_decl = False
        elif ch == "}":
            if stack:
                stack.pop()
        elif ch == ";":
            pending_decl = False
    return pending_decl


def file_block(lines, i, out):
    """The comment block after `#pragma once`: the file's documentation. Returns the next index."""
    j = i
    while j < len(lines) and COMMENT.match(lines[j]):
        j += 1
    if j == i:
        out.append("")
        return i
    out.append("/** @file")
    texts = escape("\n".join(COMMENT.match(lines[k]).group(2) for k in range(i, j))).split("\n")
    for k, text in enumerate(texts):
        out.append(text + (" */" if k == len(texts) - 1 else ""))
    return j


DECLARATOR = r"\w+(?:\s*=\s*[^,;{}()]+|\{[^{}]*\})?"
MULTI = re.compile(r"^(\s*)((?:(?:extern|static|constexpr|const|inline|mutable)\s+)*[\w:]+(?:<[^;]*>)?)\s+("
                   + DECLARATOR + r"(?:\s*,\s*" + DECLARATOR + r")+);\s*$")


def split_declarators(code, doc, first_documented):
    """`T a = 1, b = 2;` as `T a = 1; T b = 2;` (one member each, on one line), every declarator
    after the first (or all when `first_documented` is false) with the trailing doc `doc`."""
    m = MULTI.match(code)
    if not m:
        return None
    parts, depth, cur = [], 0, ""
    for ch in m.group(3):
        depth += ch == "{"
        depth -= ch == "}"
        if ch == "," and depth == 0:
            parts.append(cur.strip())
            cur = ""
        else:
            cur += ch
    parts.append(cur.strip())
    out = []
    for k, d in enumerate(parts):
        out.append(f"{m.group(2)} {d};" + (f" /**< {doc} */" if (k > 0 or not first_documented) else ""))
    return m.group(1) + " ".join(out)


CLOSE_VAR = re.compile(r"^\s*\}\s*\w+[^;{}]*;\s*$")
ENUM_VAR = re.compile(r"^\s*enum\b[^{]*\{[^}]*\}\s*\w+[^;]*;\s*$")


def join_continued_declarators(lines):
    """`T a, b,` / `    c;` (one declaration over two lines) on one line, an empty line after."""
    out = list(lines)
    for k in range(len(out) - 1):
        code, nxt = code_of(out[k]).rstrip(), code_of(out[k + 1]).strip()
        if code.endswith(",") and "(" not in code and nxt.endswith(";") and "(" not in nxt \
                and "//" not in out[k] and "//" not in out[k + 1] and MULTI.match(code + " " + nxt):
            out[k], out[k + 1] = code + " " + nxt, ""
    return out


class Filter:
    def __init__(self, lines):
        self.lines = join_continued_declarators(lines)
        self.out = []
        self.stack, self.pending = [], False
        self.trailing_col = -1  # column of the last trailing comment, for its continuation lines
        self.run_doc = None  # the doc of the block above a run of declarations
        self.run_first_done = False  # the run's first statement has ended
        self.close_doc = None  # the comment above `} name = ...;` (an enum's variable)

    def comment_block(self, i):
        lines, out = self.lines, self.out
        m = COMMENT.match(lines[i])
        if self.trailing_col >= 0 and len(m.group(1)) == self.trailing_col:
            out[-1] += " " + escape(m.group(2))  # continues the trailing comment of the line above
            out.append("")
            return i + 1
        j = i
        while j < len(lines) and COMMENT.match(lines[j]):
            j += 1
        nxt = lines[j] if j < len(lines) else ""
        if CLOSE_VAR.match(code_of(nxt)):  # `// text` above `} kind = ...;`: the variable's doc
            self.close_doc = " ".join(escape(COMMENT.match(lines[k]).group(2)) for k in range(i, j))
        documents = doc_scope(self.stack) and nxt.strip() and not nxt.lstrip().startswith(("#", "}"))
        raw = [COMMENT.match(lines[k]) for k in range(i, j)]
        texts = escape("\n".join(c.group(2) for c in raw)).split("\n")  # quotes may span lines
        for c, text in zip(raw, texts):
            out.append(c.group(1) + ("/// " + text if documents else "// " + c.group(2)))
        self.trailing_col = -1
        self.run_doc = " ".join(texts) if documents else None
        self.run_first_done = False
        return j

    def code_line(self, line):
        code = code_of(line)
        t = TRAILING.match(line)
        has_trailing = bool(t) and code.rstrip() == code_of(t.group(1)).rstrip()
        at_doc = doc_scope(self.stack) and not line.lstrip().startswith("#")
        balanced = code.count("{") == code.count("}")
        ends = code.rstrip().endswith(";") or (balanced and "{" in code and code.rstrip().endswith("}"))
        if not line.strip() or not balanced or code.lstrip().startswith(("}", "#", "public", "private")):
            self.run_doc = None
        out = line
        if self.close_doc and CLOSE_VAR.match(code):
            out = line.rstrip() + f" /**< {self.close_doc} */"
        self.close_doc = None
        if at_doc and self.run_doc is not None and ENUM_VAR.match(code) and not has_trailing:
            out = line.rstrip() + f" /**< {self.run_doc} */"  # the block documents the enum; this, the variable
            self.run_first_done = True
            self.pending = braces(code, self.stack, self.pending)
            self.out.append(out)
            return
        if has_trailing and at_doc:
            lead, doc = t.group(1), escape(t.group(3))
            split = split_declarators(lead, doc, False)
            out = split if split else lead + t.group(2) + "///< " + doc
            if SCOPE.search(lead) and lead.rstrip().endswith("{"):  # `struct X {  // text`
                indent = lead[: len(lead) - len(lead.lstrip())]
                out = f"{indent}/** {doc} */ {lead.strip()}"
            self.trailing_col = len(lead) + len(t.group(2)) if not split else -1
            self.run_doc = None  # a member with its own comment ends the run of the block above
        else:
            self.trailing_col = -1
            if at_doc and self.run_doc is not None:
                split = split_declarators(code, self.run_doc, not self.run_first_done)
                if split:
                    out = split
                elif self.run_first_done and ends:
                    out = line.rstrip() + f" /**< {self.run_doc} */"
                self.run_first_done = self.run_first_done or ends
            elif at_doc and code.strip():
                split = split_declarators(code, "", True)
                out = split.replace(" /**<  */", "") if split else out  # undocumented: left to warn
        self.pending = braces(code, self.stack, self.pending)
        self.out.append(out)

    def run(self):
        i = 0
        while i < len(self.lines):
            line = self.lines[i]
            if line.strip() == "#pragma once":
                i = file_block(self.lines, i + 1, self.out)
            elif COMMENT.match(line):
                i = self.comment_block(i)
            else:
                self.code_line(line)
                i += 1
        return "\n".join(self.out)


def main(path):
    with open(path, encoding="utf-8") as f:
        sys.stdout.write(Filter(f.read().split("\n")).run())


if __name__ == "__main__":
    main(sys.argv[1])
