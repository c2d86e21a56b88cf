#!/usr/bin/env python3
"""Every relative link and anchor in README.md and docs/ resolves.

A link [text](path#anchor) or ![alt](path) must name a file or folder of the tree; its anchor, and a
bare (#anchor), must be a heading of the target page as GitHub names it (lower case, punctuation but
'-' and '_' dropped, spaces as '-', a repeated heading suffixed -1, -2, ...) or an explicit
<a name="..."> / id="...". Links to other sites are not fetched (CI has no network).
Every picture under docs/ (.png, .svg, .gif) must be linked or shown by some page, so that no chart is
left behind when a page is rewritten.
README's "Known limits" has at most 8 bullets of at most 240 characters each.
Usage: doc_links_test.py [repository root]; prints each broken link and exits 1 if there is one.
"""
import os
import re
import sys

LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
HEADING = re.compile(r'^(#{1,6})\s+(.*?)\s*#*\s*$')
EXPLICIT = re.compile(r'<a\s+(?:name|id)="([^"]+)"|\sid="([^"]+)"')
FENCE = re.compile(r'^\s*(```|~~~)')


def slug(text):
    text = re.sub(r'<[^>]+>', '', text)                      # inline HTML
    text = re.sub(r'!?\[([^\]]*)\]\([^)]*\)', r'\1', text)  # links keep their text
    text = text.replace('`', '').strip().lower()
    text = ''.join(c for c in text if c.isalnum() or c in ' -_')
    return text.replace(' ', '-')


def prose_lines(path):
    """The page's lines outside fenced code blocks."""
    fenced = False
    with open(path, encoding='utf-8') as page:
        for number, line in enumerate(page, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if not fenced:
                yield number, line


def anchors(path, cache={}):
    if path not in cache:
        names, seen = set(), {}
        for _, line in prose_lines(path):
            heading = HEADING.match(line)
            if heading:
                base = slug(heading.group(2))
                count = seen.get(base, 0)
                seen[base] = count + 1
                names.add(base if count == 0 else f'{base}-{count}')
            for match in EXPLICIT.finditer(line):
                names.add(match.group(1) or match.group(2))
        cache[path] = names
    return cache[path]


def pages(root):
    yield os.path.join(root, 'README.md')
    for folder, _, files in os.walk(os.path.join(root, 'docs')):
        for name in sorted(files):
            if name.endswith('.md'):
                yield os.path.join(folder, name)


def known_limits_problems(readme):
    """README's "Known limits" stays a list a reader takes in: at most 8 bullets of 240 characters."""
    problems, bullets, inside = [], 0, False
    for number, line in prose_lines(readme):
        heading = HEADING.match(line)
        if heading:
            inside = heading.group(2).strip().lower() == 'known limits'
        elif inside and line.startswith('- '):
            bullets += 1
            if len(line.rstrip()) > 240:
                problems.append(f'README.md:{number}: a known limit of {len(line.rstrip())} characters (at most 240)')
    if bullets > 8:
        problems.append(f'README.md: {bullets} known limits (at most 8)')
    return problems


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', '..'))
    broken, checked, linked = [], 0, set()
    for page in pages(root):
        for number, line in prose_lines(page):
            line = re.sub(r'`[^`]*`', '', line)  # code spans are not links
            for match in LINK.finditer(line):
                target = match.group(1)
                if re.match(r'^[a-z][a-z0-9+.-]*:', target):  # http:, https:, mailto:
                    continue
                checked += 1
                path, _, anchor = target.partition('#')
                resolved = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
                linked.add(resolved)
                where = f'{os.path.relpath(page, root)}:{number}: ({target})'
                if not os.path.exists(resolved):
                    broken.append(f'{where} names {os.path.relpath(resolved, root)}, which does not exist')
                elif anchor and resolved.endswith('.md') and anchor not in anchors(resolved):
                    broken.append(f'{where}: {os.path.relpath(resolved, root)} has no heading or anchor "{anchor}"')
    pictures = 0
    for folder, _, files in os.walk(os.path.join(root, 'docs')):
        for name in sorted(files):
            if name.lower().endswith(('.png', '.svg', '.gif')):
                pictures += 1
                picture = os.path.normpath(os.path.join(folder, name))
                if picture not in linked:
                    broken.append(f'{os.path.relpath(picture, root)} is shown or linked by no page')
    broken += known_limits_problems(os.path.join(root, 'README.md'))
    for line in broken:
        print(line)
    print(f'doc links: {checked} checked, {pictures} pictures, {len(broken)} broken')
    return 1 if broken or checked == 0 else 0


if __name__ == '__main__':
    sys.exit(main())
