"""A page shaped like Gradescope's autograder results, rendered from a results.json clothref wrote,
so a browser test can check and picture what a student sees there (docs/grading-reference.md, Gradescope).

Gradescope's layout, as its documentation shows it: the total (the sum of the tests' scores over
the sum of their max_score when the file's `score` is absent, else `score`) at the top right, the
top-level `output` under "Autograder Output", then one block per test, titled "name (score/max)",
green when it has full marks, red otherwise, its `output` below. Outputs are rendered by their
`output_format`: `html` as it is, `md` through python3-markdown (tables, fenced code), `text` in a
<pre>. Tests whose `visibility` is `hidden` are left out, as students would not see them.

A test's `output_format` may differ from the others' (Gradescope reads it per test): clothref gives
`html` for a failed check with a picture (inline SVG, then its text escaped) and `md` for the rest.

    render(results: dict) -> str        the page (no script of its own, no external resource)
    active_content(page: str) -> list   whatever in a page could run or load: script, iframe,
                                        object, embed, link, base, meta refresh, form elements,
                                        on* attributes, javascript: and external URLs
"""
import html
import html.parser

import markdown


def _output(text, output_format):
    if output_format == 'html':
        return text
    if output_format in ('md', 'simple_format'):
        return markdown.markdown(text, extensions=['tables', 'fenced_code'])
    return f'<pre>{html.escape(text)}</pre>'


def _number(value):
    return f'{value:g}'


STYLE = """
body { font-family: Helvetica, Arial, sans-serif; margin: 0; color: #1f2a36; background: #f4f6f8; }
header { background: #2d3e50; color: #fff; padding: 10px 24px; font-size: 18px; }
main { display: flex; gap: 24px; padding: 20px 24px; }
.gs-results { flex: 1; min-width: 0; }
.gs-side { width: 220px; }
.gs-total { background: #fff; border: 1px solid #d5dbe1; padding: 14px; font-size: 15px; }
.gs-total strong { display: block; font-size: 28px; margin-top: 4px; }
h2 { font-size: 17px; margin: 18px 0 8px; }
.gs-box { background: #fff; border: 1px solid #d5dbe1; padding: 10px 14px; margin-bottom: 8px; }
.gs-test > .gs-title { font-weight: bold; padding: 6px 10px; margin: -10px -14px 8px; }
.gs-passed > .gs-title { background: #e5f4e9; border-left: 5px solid #2e8540; }
.gs-failed > .gs-title { background: #fbe9e7; border-left: 5px solid #c0392b; }
table { border-collapse: collapse; font-size: 13px; }
td, th { border: 1px solid #d5dbe1; padding: 2px 8px; text-align: left; }
pre, code { font-size: 12px; white-space: pre-wrap; }
"""


def render(results):
    tests = [t for t in results.get('tests', []) if t.get('visibility', 'visible') != 'hidden']
    maximum = sum(t.get('max_score', 0) for t in tests)
    score = results.get('score', sum(t.get('score', 0) for t in tests))
    blocks = []
    for t in tests:
        full = t.get('score', 0) >= t.get('max_score', 0)
        title = f"{html.escape(t['name'])} ({_number(t.get('score', 0))}/{_number(t.get('max_score', 0))})"
        blocks.append(f'<section class="gs-box gs-test {"gs-passed" if full else "gs-failed"}">'
                      f'<div class="gs-title">{title}</div>'
                      f'{_output(t.get("output", ""), t.get("output_format", "text"))}</section>')
    top = results.get('output', '')
    return ('<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
            f'<title>Autograder Results</title><style>{STYLE}</style></head><body>'
            '<header>Autograder Results</header><main><div class="gs-results">'
            + (f'<h2>Autograder Output</h2><div class="gs-box gs-output">'
               f'{_output(top, results.get("output_format", "text"))}</div>' if top else '')
            + f'<h2>Tests ({len(tests)})</h2>' + ''.join(blocks) + '</div>'
            f'<aside class="gs-side"><div class="gs-total">Autograder Score<strong id="gs-score">'
            f'{_number(score)} / {_number(maximum)}</strong></div></aside></main></body></html>')


class _Active(html.parser.HTMLParser):
    RUNS = {'script', 'iframe', 'frame', 'object', 'embed', 'link', 'base', 'form', 'applet',
            'foreignobject', 'animate', 'set', 'use', 'image'}

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.found = []

    def handle_starttag(self, tag, attrs):
        if tag in self.RUNS or (tag == 'meta' and any(n == 'http-equiv' for n, _ in attrs)):
            self.found.append(f'<{tag}>')
        for name, value in attrs:
            value = (value or '').strip().lower()
            if name.startswith('on'):
                self.found.append(f'<{tag} {name}=...>')
            elif name in ('href', 'src', 'xlink:href', 'action', 'formaction', 'srcset',
                          'background', 'poster', 'data'):
                self.found.append(f'<{tag} {name}={value[:40]}>')
            elif 'url(' in value and 'url(#' not in value:
                self.found.append(f'<{tag} {name}={value[:40]}>')
            elif value.startswith('javascript:'):
                self.found.append(f'<{tag} {name}=javascript:...>')


def active_content(page):
    """Everything in `page` that could run or load something (empty for an inert page)."""
    parser = _Active()
    parser.feed(page)
    parser.close()
    return parser.found
