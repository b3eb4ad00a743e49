#!/usr/bin/env python3
"""Lists the functions in src/ longer than the project's limit (docs/architecture.md: small functions).

    python3 scripts/function-lengths.py            checks src/ against scripts/function-lengths.allow
    python3 scripts/function-lengths.py --list     lists every function over the limit, longest first

A function's length is counted in lines, from the first line of its signature to its closing brace.
The check fails on a function over the limit that the allow-list does not name, and on an allow-list
entry that is no longer over the limit (or no longer exists): the list only shrinks. The CTest test
CodeHealth.FunctionLengths runs the check.

The parser is a small brace matcher, not a compiler: comments, string and character literals are
blanked, then each '{' outside a function body is classified by the text before it (namespace,
class, a constructor's braced member initialiser, or a function body, named by the qualified
identifier in front of its parameter list). Lambdas and blocks inside a function count toward it.
"""
import argparse
import pathlib
import re
import sys

LIMIT = 60
ROOT = pathlib.Path(__file__).resolve().parent.parent


def blank_comments_and_literals(text):
    """The text with comments and string/char literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i))
            i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(')' + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        elif c in '"\'':
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator: 1'000
                out.append(' ')
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            j = min(j + 1, n)
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return ''.join(out)


def strip_preprocessor(text):
    """Preprocessor lines (and their continuations) blanked."""
    lines = text.split('\n')
    inside = False
    for k, line in enumerate(lines):
        if inside or line.lstrip().startswith('#'):
            inside = line.rstrip().endswith('\\')
            lines[k] = ''
    return '\n'.join(lines)


def function_name(header):
    """The qualified name in front of the parameter list of a function header (the first '(' outside
    template brackets), or None."""
    header = re.sub(r'\[\[[^\]]*\]\]', ' ', header)
    angle = 0
    for i, c in enumerate(header):
        if c == '<':
            angle += 1
        elif c == '>':
            angle = max(angle - 1, 0)
        elif c == '(' and angle == 0:
            m = re.search(r'((?:[A-Za-z_]\w*\s*(?:<[^<>()]*>)?\s*::\s*)*~?(?:operator\s*\S+?|[A-Za-z_]\w*))\s*$',
                          header[:i])
            return re.sub(r'\s+', '', m.group(1)) if m else None
    return None


def classify(header, in_init_list):
    """What the '{' after `header` opens: namespace, class, init (a braced member initialiser,
    the header kept), function, or other."""
    h = ' '.join(header.split())
    if re.match(r'^(inline\s+)?namespace\b', h) or h.startswith('extern "C"') or h == 'extern':
        return 'namespace'
    if re.search(r'\b(class|struct|union|enum)\b', h) and '(' not in h.split('{')[0].split('=')[0]:
        return 'class'
    if in_init_list and re.search(r'[\w>]\s*$', h):
        return 'init'
    if ')' in h and not re.search(r'=\s*$', h) and function_name(h):
        return 'function'
    return 'other'


def functions_in(path):
    """(name, first line, last line) of each function defined in the file."""
    text = strip_preprocessor(blank_comments_and_literals(path.read_text()))
    found = []
    stack = []  # kinds of the open braces
    header_start = 0
    current = None  # (name, first line, depth) of the function being read
    line = 1
    for i, c in enumerate(text):
        if c == '\n':
            line += 1
        if current is not None:
            if c == '{':
                stack.append('block')
            elif c == '}':
                stack.pop()
                if len(stack) == current[2]:
                    found.append((current[0], current[1], line))
                    current = None
                    header_start = i + 1
            continue
        if c in ';':
            header_start = i + 1
        elif c == '{':
            header = text[header_start:i]
            in_init = bool(re.search(r'\)\s*(noexcept\s*)?:[^:]', ' '.join(header.split())))
            kind = classify(header, in_init)
            if kind == 'function':
                first = text.count('\n', 0, header_start + len(header) - len(header.lstrip())) + 1
                current = (function_name(header) or '?', first, len(stack))
                stack.append('function')
            else:
                stack.append(kind)
                if kind != 'init':
                    header_start = i + 1
        elif c == '}':
            kind = stack.pop() if stack else 'other'
            if kind != 'init':
                header_start = i + 1
    return found


def long_functions(src):
    rows = []
    for path in sorted(src.rglob('*')):
        if path.suffix in ('.cpp', '.hpp', '.h') and path.is_file():
            for name, first, last in functions_in(path):
                length = last - first + 1
                if length > LIMIT:
                    rows.append((str(path.relative_to(ROOT)), name, length, first))
    return rows


def read_allow_list(path):
    """{(file, function): reason} from lines 'FILE FUNCTION  reason' ('#' starts a comment)."""
    allowed = {}
    for raw in path.read_text().splitlines():
        entry = raw.split('#', 1)[0].strip()
        if entry:
            parts = entry.split(None, 2)
            allowed[(parts[0], parts[1])] = parts[2] if len(parts) > 2 else ''
    return allowed


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--list', action='store_true', help='list the long functions, longest first')
    parser.add_argument('--allow', default=str(ROOT / 'scripts' / 'function-lengths.allow'))
    args = parser.parse_args()
    rows = long_functions(ROOT / 'src')
    if args.list:
        for file, name, length, first in sorted(rows, key=lambda r: -r[2]):
            print(f'{length:4d}  {file}:{first}  {name}')
        return 0
    allowed = read_allow_list(pathlib.Path(args.allow))
    failures = []
    for file, name, length, first in rows:
        if (file, name) not in allowed:
            failures.append(f'{file}:{first}: {name} is {length} lines (limit {LIMIT}): split it '
                            f'into named helpers (or, with a reason, add it to {args.allow})')
    seen = {(file, name) for file, name, _, _ in rows}
    for key in allowed:
        if key not in seen:
            failures.append(f'{key[0]} {key[1]}: no longer over {LIMIT} lines; remove it from {args.allow}')
    for f in failures:
        print(f, file=sys.stderr)
    print(f'{len(rows)} functions over {LIMIT} lines in src/, {len(allowed)} allowed; '
          f'{len(failures)} problems')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
