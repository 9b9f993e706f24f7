"""`clothref grade --html`, the report a student reads, in headless Chromium (ctest browser_report;
tools/grader/grade/report/html_report.cpp, tools/pages/assets/report.html).

Usage: report_page_test.py --cli build/bin/clothref --source SOURCE_DIR --cache DIR --screenshots DIR

Grades the corpus's 2022 reference with the mutant cloth-normal-reversed's sphere.cpp (collision
normal reversed: Spheres::collide(Cloth*) loses points, cause collision-normal-sign) and checks:
no console message, no network request, the stub table; the stub as a student reads it: its points
and the rule that gave them, what is wrong (the cause named once), the failed checks as a table
(check, expected, yours, by how much) and a picture of the state each tried, each check folded
below with its badge, the passed checks folded; the whole run's viewer mounted side by side with
four stills that are not blank, and results.json's top-level output is HTML, as are the failed
checks with a picture (the others stay Markdown). Then the same results.json as Gradescope shows it
(gradescope_page.py): the total, one block per test, the failed ones red with their Markdown
rendered, a visible picture in each HTML test, and nothing on the page that could run.
Screenshots: report.png, report-stub.png (one stub's feedback at 1280 px), report-sketch.png,
report-whole-run.png, gradescope-results.png, gradescope-picture.png.
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser  # noqa: E402
import gradescope_page  # noqa: E402


def main():
    options, checks = browser.start('--source', '--cache')
    corpus = os.path.join(options.source, 'tests', 'grader', 'submissions', '2022')
    with tempfile.TemporaryDirectory(prefix='clothref-report-test-') as tmp:
        sub = os.path.join(tmp, 'normal-reversed')
        shutil.copytree(os.path.join(corpus, 'reference'), sub)
        for name in glob.glob(os.path.join(sub, '**', '*.json'), recursive=True):
            os.remove(name)
        shutil.copy(os.path.join(corpus, 'cloth-normal-reversed', 'sphere.cpp'),
                    glob.glob(os.path.join(sub, '**', 'sphere.cpp'), recursive=True)[0])
        page, results = os.path.join(tmp, 'report.html'), os.path.join(tmp, 'results.json')
        result = subprocess.run([options.cli, 'grade', sub, '--cache-dir', options.cache,
                                 '--html', page, '--results', results],
                                capture_output=True, text=True)
        checks.check(result.returncode == 0 and os.path.isfile(page),
                     f'graded with --html: {result.stderr.strip()}')
        if not os.path.isfile(page):
            checks.finish()
        with open(results) as f:
            data = json.load(f)
        checks.check(data.get('output_format') == 'html' and '<table>' in data.get('output', ''),
                     "results.json: the top-level output is HTML")
        # a failed check with a picture is HTML (the picture inline), every other stays Markdown
        html_tests = [t for t in data['tests'] if t.get('output_format') == 'html']
        collide = [t for t in data['tests']
                   if t['tags'][0] == 'Spheres::collide(Cloth*)' and t['status'] == 'failed']
        checks.check(all(t.get('output_format') in ('md', 'html') for t in data['tests']) and
                     all(t['status'] == 'failed' and '<svg ' in t['output'] for t in html_tests) and
                     collide and all(t.get('output_format') == 'html' for t in collide),
                     f'results.json: {len(html_tests)} failed checks with a picture are HTML '
                     f'({len(collide)} collision checks among them), the others Markdown')
        b = browser.Browser(height=1400)
        try:
            url = b.open(page)
            rows = b.js("return [...document.querySelectorAll('.gr-stubs tr')].map("
                        "(tr) => [...tr.cells].map((c) => c.textContent))")
            collide = [r for r in rows if r and r[0] == 'Spheres::collide(Cloth*)']
            checks.check(len(rows) == 9 and collide and collide[0][2] != '8 of 8',
                         f'stub table: {len(rows) - 1} stubs, collide(Cloth*) {collide}')
            # the stub a student reads in a minute: its points and the rule, what is wrong once,
            # the failed checks as a table, the pictures, then each check folded
            section = "const h = document.getElementById('Spheres::collide(Cloth*)'); const out = [];" \
                      "for (let e = h.nextElementSibling; e && e.tagName !== 'H2'; e = e.nextElementSibling)" \
                      " out.push(e); return out"
            points = b.js(section + ".filter((e) => e.classList.contains('gr-points'))"
                          ".map((e) => e.textContent)")
            checks.check(len(points) == 1 and ' checks passed' in points[0] and
                         ('rubric: per-mistake' in points[0] or 'scored per check' in points[0]),
                         f'the stub says its points and the rule that gave them: {points}')
            likely = b.js(section + ".filter((e) => e.classList.contains('gr-likely'))"
                          ".map((e) => e.textContent)")
            said = likely[0].count('collision-normal-sign') if likely else 0
            checks.check(len(likely) == 1 and said == 1,
                         f'what is wrong, once: collision-normal-sign named {said} time(s)')
            rows = b.js(section + ".flatMap((e) => [...e.querySelectorAll('.gr-failed tr')])"
                        ".map((tr) => [...tr.cells].map((c) => c.textContent))")
            failed = b.js(section + ".filter((e) => e.matches('details.gr-check'))"
                          ".map((d) => d.querySelector('summary').textContent)")
            checks.check(len(rows) == len(failed) + 1 and len(failed) > 0 and
                         rows[0] == ['failed check', 'expected', 'yours', 'by how much'] and
                         all(r[1] and r[2] and r[3] for r in rows[1:]),
                         f'the failed checks as a table: {len(rows) - 1} rows for {len(failed)} '
                         f'failed checks, each with expected, yours and by how much')
            checks.check(all('collision-normal-sign' in f for f in failed),
                         f'{len(failed)} failed checks folded below, each with its badge')
            # each failed collision check pictures the state it tried: one static SVG, drawn
            sketches = b.js(section + ".flatMap((e) => [...e.querySelectorAll('.gr-picture svg.gr-sketch')])"
                            ".length")
            checks.check(sketches == len(failed),
                         f'a picture of the state tried for each failed check ({sketches})')
            if sketches:
                b.js("document.querySelector('.gr-picture svg.gr-sketch').scrollIntoView()")
                sketch = browser.non_background_fraction(
                    b.element_image('.gr-picture svg.gr-sketch'))
                checks.check(sketch > 0.02, f'the first picture is drawn ({sketch:.0%})')
                b.save_screenshot(os.path.join(options.screenshots, 'report-sketch.png'))
            # one stub's feedback, as a student sees it at 1280 px
            b.driver.set_window_size(1280, 1100)
            b.js("document.getElementById('Spheres::collide(Cloth*)').scrollIntoView()")
            b.save_screenshot(os.path.join(options.screenshots, 'report-stub.png'))
            b.driver.set_window_size(1200, 1400)
            b.js("window.scrollTo(0, 0)")
            passed = b.js("return document.querySelectorAll('details.gr-passed details.gr-check').length")
            checks.check(passed > 20, f'{passed} passed checks, folded')
            b.save_screenshot(os.path.join(options.screenshots, 'report.png'))
            ready = b.js("const v = document.getElementById('whole-run');"
                         "return v ? v.dataset.ready === '1' : false")
            checks.check(ready, 'the whole run viewer mounted')
            layout = b.js("const s = document.querySelector('.cv-layout'); return s && s.value")
            checks.check(layout == 'side', f'student and reference side by side ({layout})')
            stills = b.driver.find_elements('css selector', '.cv-still canvas')
            checks.check(len(stills) == 4, f'{len(stills)} stills of the whole run')
            b.js("document.getElementById('whole-run').scrollIntoView()")
            drawn = [browser.non_background_fraction(b.element_image(f'.cv-still:nth-child({k}) canvas'))
                     for k in range(1, len(stills) + 1)]
            checks.check(drawn and min(drawn) > 0.1,
                         'every still shows the cloth and spheres (' +
                         ', '.join(f'{d:.0%}' for d in drawn) + ' drawn)')
            b.save_screenshot(os.path.join(options.screenshots, 'report-whole-run.png'))
            browser.check_quiet(b, checks, url, 'report')
            check_gradescope_page(b, checks, data, os.path.join(tmp, 'gradescope.html'),
                                  os.path.join(options.screenshots, 'gradescope-results.png'))
        finally:
            b.close()
    checks.finish()


def check_gradescope_page(b, checks, data, page, screenshot):
    """results.json rendered as Gradescope's results page: what the student sees there."""
    with open(page, 'w', encoding='utf-8') as f:
        f.write(gradescope_page.render(data))
    url = b.open(page)
    tests = data['tests']
    maximum = sum(t['max_score'] for t in tests)
    shown = b.js("return document.getElementById('gs-score').textContent")
    checks.check(shown == f"{data['score']:g} / {maximum:g}",
                 f'Gradescope page: the total {shown!r} is results.json\'s score over the tests\' max')
    titles = b.js("return [...document.querySelectorAll('.gs-test .gs-title')].map("
                  "(t) => t.textContent)")
    checks.check(len(titles) == len(tests) and all(
        title.startswith(t['name']) for title, t in zip(titles, tests)),
                 f'Gradescope page: one block per test, in order ({len(titles)} of {len(tests)})')
    failed = b.js("return [...document.querySelectorAll('.gs-failed')].map((t) => t.textContent)")
    lost = [t for t in tests if t['score'] < t['max_score']]
    checks.check(len(failed) == len(lost) and len(lost) > 0 and
                 all('collision-normal-sign' in f for f in failed),
                 f'Gradescope page: {len(failed)} red blocks (tests short of full marks: '
                 f'{len(lost)}), each naming collision-normal-sign')
    markup = b.js("return document.querySelectorAll('.gs-test table, .gs-test code, "
                  ".gs-test strong').length")
    checks.check(markup > 0, f'Gradescope page: the tests\' Markdown is rendered ({markup} elements)')
    # one row per stub that lost points (here one) under the head, the others on one line
    table = b.js("return [...document.querySelectorAll('.gs-output table tr')]"
                 ".map((tr) => tr.cells[0].textContent)")
    files = b.js("return document.querySelectorAll('.gs-output table').length")
    listed = b.js("return document.querySelectorAll('.gs-output li code').length")
    passed = b.js("return [...document.querySelectorAll('.gs-output p')].map((p) => p.textContent)"
                  ".filter((t) => t.startsWith('Every check passed: '))")
    checks.check(table == ['stub', 'Spheres::collide(Cloth*)'] and files == 1 and listed >= 3 and
                 len(passed) == 1 and passed[0].count(' / ') == 7,
                 f'Gradescope page: the HTML output has a row per stub that lost points ({table}), '
                 f'the others on one line ({passed}), and the files, each path in code ({listed})')
    raw = b.js("return document.body.textContent.includes('|---')")
    checks.check(not raw, 'Gradescope page: no Markdown table left unrendered')
    # the pictures: one per HTML test, drawn, and nothing on the page can run
    pictures = b.js("return [...document.querySelectorAll('.gs-test')].filter("
                    "(t) => t.querySelector('svg.gr-sketch')).length")
    wanted = sum(1 for t in tests if t.get('output_format') == 'html')
    checks.check(pictures == wanted and wanted > 0,
                 f'Gradescope page: a picture in each HTML test ({pictures} of {wanted})')
    if pictures:
        b.js("document.querySelector('.gs-failed svg.gr-sketch').scrollIntoView()")
        size = b.js("const r = document.querySelector('.gs-failed svg.gr-sketch')"
                    ".getBoundingClientRect(); return [r.width, r.height]")
        drawn = browser.non_background_fraction(b.element_image('.gs-failed svg.gr-sketch'))
        checks.check(size[0] > 200 and size[1] > 150 and drawn > 0.02,
                     f'Gradescope page: the first picture is visible ({size[0]:.0f} x '
                     f'{size[1]:.0f} px, {drawn:.0%} drawn)')
        b.save_screenshot(os.path.join(os.path.dirname(screenshot), 'gradescope-picture.png'))
        b.js("window.scrollTo(0, 0)")
    scripts = b.js("return document.scripts.length")
    handlers = b.js("return [...document.querySelectorAll('*')].flatMap((e) => "
                    "[...e.attributes].map((a) => a.name)).filter((n) => n.startsWith('on'))")
    active = gradescope_page.active_content(gradescope_page.render(data))
    checks.check(scripts == 0 and not handlers and not active,
                 f'Gradescope page: nothing can run ({scripts} scripts, handlers {handlers}, '
                 f'{active})')
    # tall enough to show the total, the summary and the first red blocks in one picture
    b.driver.set_window_size(1200, 2300)
    b.save_screenshot(screenshot)
    browser.check_quiet(b, checks, url, 'Gradescope page')


if __name__ == '__main__':
    main()
