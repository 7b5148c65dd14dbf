#!/usr/bin/env python3
# Functions longer than N lines (default 100) in src/ and include/, longest first, by brace
# matching: a "{" opened at namespace or class scope after a ")" starts a function body.
#   python3 scripts/long_functions.py [N]      (run from the repository root)
import re, sys, glob
N = int(sys.argv[1]) if len(sys.argv) > 1 else 100
out = []
for f in sorted(glob.glob('src/**/*.cpp', recursive=True) + glob.glob('include/**/*.hpp', recursive=True)):
    text = open(f).read()
    lines = text.split('\n')
    stack = []  # kinds: 'scope' (namespace/class/struct/extern) or ('func', line, name) or 'block'
    pending = ''  # code since the last ; { or } at scope level
    for i, l in enumerate(lines):
        code = re.sub(r'//.*', '', re.sub(r'"(\\.|[^"\\])*"', '""', re.sub(r"'(\\.|[^'\\])*'", "''", l)))
        if code.lstrip().startswith('#'): continue
        for ch in code:
            if ch == '{':
                at_scope = all(k == 'scope' for k in stack)
                head = pending.strip()
                if at_scope and re.search(r'\b(namespace|struct|class|union|enum)\b[^()]*$', head) or (at_scope and head.startswith('extern')):
                    stack.append('scope')
                elif at_scope and ')' in head and not head.rstrip().endswith('='):
                    m = re.findall(r'([A-Za-z_~][A-Za-z_0-9:<>,~ ]*?)\s*\(', head)
                    stack.append(('func', i + 1, m[0].split()[-1] if m else head[:40]))
                else:
                    stack.append('block')
                pending = ''
            elif ch == '}':
                k = stack.pop() if stack else None
                if isinstance(k, tuple):
                    n = i + 1 - k[1] + 1
                    if n > N: out.append((n, f, k[1], k[2]))
                pending = ''
            elif ch == ';':
                if all(k == 'scope' for k in stack): pending = ''
                else: pending += ch
            else:
                pending += ch
        pending += ' '
for n, f, s, name in sorted(out, reverse=True): print(f"{n:5d} {f}:{s} {name}")
