"""No element a student wrote: a hostile submission's results.json and report.md rendered as
Gradescope renders them (tests/browser/gradescope_page.py: Markdown through python3-markdown, HTML
as it is) hold no element or attribute the submission put in its text (ctest markdown_safety;
docs/grading-reference.md, "Gradescope").

Usage: markdown_safety_test.py --cli build/bin/clothref --source SOURCE_DIR --cache DIR

The submission (the 2022 reference, then):
  - cloth.cpp does not compile: a static_assert whose message holds a ``` line and an <img>;
  - Spheres::collide(Cloth*) prints a ``` line and an <img> to stderr and aborts, beside an `auto`
    Eigen expression whose line ends in a comment with backticks and an <img> (the quoted line);
  - a second integrator.cpp in a folder named <img src=x onerror=alert(4)> (the note naming it);
  - the submission's own folder is named with an <img> and U+202E (the report's heading).
Checks: every output is graded (exit 0); in the rendered results page and report.md there is no
<img>, no <script>, no attribute named on*, nothing that could run or load
(gradescope_page.active_content; a test given as HTML included); the hostile texts are there as
text; U+202E is shown escaped. No browser is needed: skipped (77) only without python3-markdown.
"""
import argparse
import html.parser
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

SKIP = 77


class Elements(html.parser.HTMLParser):
    """Every start tag and attribute name of a page."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags, self.attributes, self.text = [], [], []

    def handle_starttag(self, tag, attrs):
        # our own pictures (class gr-sketch: a failed check's state, drawn from numbers) aside
        if tag != 'svg' or not (dict(attrs).get('class') or '').startswith('gr-sketch'):
            self.tags.append(tag)
        self.attributes.extend(name for name, _ in attrs)

    def handle_data(self, data):
        self.text.append(data)


def parse(page):
    parser = Elements()
    parser.feed(page)
    return parser


def hostile_submission(source, root):
    reference = os.path.join(source, 'tools', 'grader', 'reference', '2022')
    name = os.path.join(root, 'sub <img src=x onerror=alert(0)> \u202eppc.exe')
    os.makedirs(name)
    with open(os.path.join(reference, 'cloth.cpp')) as f:
        cloth = f.read()
    cloth += ('\nstatic_assert(sizeof(int) == 3, "x\\n```\\n<img src=x onerror=alert(1)>\\n```\\n'
              '<script>alert(11)</script>");\n')
    with open(os.path.join(name, 'cloth.cpp'), 'w') as f:
        f.write(cloth)
    with open(os.path.join(reference, 'sphere.cpp')) as f:
        sphere = f.read()
    marker = 'Particles& clothParticles = cloth->particles();\n'
    assert marker in sphere
    sphere = sphere.replace(marker, marker +
                            '  auto hostile = clothParticles.position(0) - clothParticles.velocity(0);'
                            '  // `` ` </code></pre><img src=x onerror=alert(3)> ``\n'
                            '  (void)hostile;\n'
                            '  fputs("```\\n<img src=x onerror=alert(2)>\\n```\\n", stderr);\n'
                            '  abort();\n')
    sphere = '#include <cstdio>\n#include <cstdlib>\n' + sphere
    with open(os.path.join(name, 'sphere.cpp'), 'w') as f:
        f.write(sphere)
    shutil.copy(os.path.join(reference, 'integrator.cpp'), os.path.join(name, 'integrator.cpp'))
    other = os.path.join(name, '<img src=x onerror=alert(4)>')
    os.makedirs(other)
    shutil.copy(os.path.join(reference, 'integrator.cpp'), os.path.join(other, 'integrator.cpp'))
    return name


def main():
    parser = argparse.ArgumentParser()
    for option in ('--cli', '--source', '--cache'):
        parser.add_argument(option, required=True)
    options = parser.parse_args()
    try:
        import gradescope_page
    except ImportError as error:
        print(f'SKIP: python module {error.name} not installed (tools/setup.sh installs '
              'python3-markdown)')
        sys.exit(SKIP)
    import markdown
    failed = []

    def check(condition, what):
        print(('ok    ' if condition else 'FAIL  ') + what)
        if not condition:
            failed.append(what)

    with tempfile.TemporaryDirectory(prefix='clothref-markdown-test-') as tmp:
        submission = hostile_submission(options.source, tmp)
        results, report = os.path.join(tmp, 'results.json'), os.path.join(tmp, 'report.md')
        run = subprocess.run([options.cli, 'grade', submission, '--no-whole-run', '--timeout', '10',
                              '--one-submission', '--cache-dir', options.cache,
                              '--results', results, '--report', report],
                             capture_output=True, text=True)
        check(run.returncode == 0, f'graded (exit {run.returncode}): {run.stderr.strip()[-300:]}')
        if run.returncode != 0:
            sys.exit(1)
        with open(results, encoding='utf-8') as f:
            data = json.load(f)
        with open(report, encoding='utf-8') as f:
            report_md = f.read()
        verdicts = data['extra_data']['verdict']
        check(verdicts == 'compile-error', f'verdict {verdicts}')
        outputs = ' '.join(t['output'] for t in data['tests'])
        check('<img src=x onerror=alert(2)>' in outputs, "the probe's stderr is quoted")
        check('onerror=alert(3)' in outputs, 'the source line is quoted')
        check('onerror=alert(1)' in outputs + data['output'], 'the compiler error is quoted')
        pages = {
            'results.json as Gradescope shows it': gradescope_page.render(data),
            'report.md through python-markdown':
                markdown.markdown(report_md, extensions=['tables', 'fenced_code']),
        }
        for what, page in pages.items():
            elements = parse(page)
            written = [t for t in elements.tags if t in ('img', 'script', 'iframe', 'a', 'svg',
                                                         'object', 'embed', 'link', 'form')]
            check(not written, f'{what}: no element the submission wrote ({written})')
            handlers = [a for a in elements.attributes if a.startswith('on')]
            check(not handlers, f'{what}: no event handler attribute ({handlers})')
            active = gradescope_page.active_content(page)
            check(not active, f'{what}: nothing that could run or load ({active})')
            text = ''.join(elements.text)
            for k in (1, 2, 3, 4):
                check(f'onerror=alert({k})' in text, f'{what}: hostile text {k} shown as text')
            check('\u202e' not in page and '\\u{202E}' in text,
                  f'{what}: the bidi override shown escaped')
    if failed:
        print(f'{len(failed)} check(s) failed')
        sys.exit(1)
    print('all checks passed')


if __name__ == '__main__':
    main()
