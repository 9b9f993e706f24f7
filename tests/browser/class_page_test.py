"""BATCHDIR/index.html, the class overview, in headless Chromium (ctest browser_class;
tools/grader/grade/report/class_page.cpp, tools/pages/assets/class.js).

Usage: class_page_test.py --cli build/bin/clothref --screenshots DIR

A batch of 30 graded submissions of both editions (20 of 2022, 10 of 2024: the collision column's
maximum differs) and one that could not be graded is made of markers (row.json) and results.json
files with known scores and causes, as a real class has them (points such as 11.25 and 1.875,
seconds up to 59, the catalogue's longest cause ids, a long folder name), so `clothref grade ...
--out BATCHDIR` rebuilds grades.csv and index.html from them without grading anything (as it does
after an interrupted batch). Checks: no console message, no network request, 30 rows, sorting by
total (both ways) and by name, filtering by cause and by verdict, the histogram counts all 30 and
labels its bins and axes, the first line says how many were graded and how many need attention
and why, the not-gradable submission listed apart and left out of the statistics, the cause table
counts and links the right reports, a check's pass rate, causes as chips (a guess marked; two,
then a count whose tooltip lists them all), every stub column shows its maximum, the legend is the
table's caption, the page opens in under 2 s; at 1280 and 1920 px every column of the table is
visible without scrolling, no cell's text is cut (every cell, header and chip shows all its text:
its content is no wider than its box) and every row is at most two lines. Screenshots:
class-index.png, class-index-1280.png, class-index-1920.png.
"""
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser  # noqa: E402

STUBS = ['Cloth::initializeSpring', 'Cloth::computeSpringForce', 'Spheres::collide(Cloth*)',
         'Spheres::collide()', 'ExplicitEuler::integrate', 'ImplicitEuler::integrate',
         'MidpointEuler::integrate', 'RungeKuttaFourth::integrate']
# the course's points per stub (2024 has no Spheres::collide())
POINTS = {2022: [15, 20, 10, 10, 5, 2.5, 2.5, 15], 2024: [10, 25, 20, 0, 5, 2.5, 2.5, 15]}
LONG_CAUSES = ['rk4-stage-from-wrong-increment', 'position-uses-acceleration',
               'restitution-full-velocity']


def fixture(batch, subs, n=30):
    """Writes n graded folders; returns their rows as {name: (total, verdict, causes, passed)}."""
    expected = {}
    for i in range(n):
        name = f'student{i:02d}' + ('-chen-wei-ting-b10902113' if i == 5 else '')
        os.makedirs(os.path.join(subs, name))
        folder = os.path.join(batch, name)
        os.makedirs(folder)
        edition = 2022 if i < 20 else 2024
        maxima = {stub: p for stub, p in zip(STUBS, POINTS[edition]) if p}
        # quarters of each stub's points: 11.25 of 15, 1.875 of 2.5, ...
        scores = {stub: m * ((i * 7 + k * 3) % 5) / 4 for k, (stub, m) in enumerate(maxima.items())}
        causes = (['backup-aliases'] if i % 2 == 0 and i < 28 else []) + \
                 (['spring-force-sign'] if i % 6 == 1 else []) + \
                 (LONG_CAUSES if i % 10 == 4 else [])
        verdict = 'compile-error' if i in (3, 17) else 'timed-out' if i == 9 else 'graded'
        passed = i % 3 != 0  # "RungeKuttaFourth::integrate: convergence order"
        total = sum(scores.values())
        row = {'submission': name, 'dir': os.path.join(subs, name), 'edition': edition,
               'stub_scores': scores, 'stub_max': maxima,
               'total': total, 'max': 80.0, 'verdict': verdict, 'isolation': 'rlimits only',
               'problem': '', 'seconds': 10.0 + i * 1.7 + (0.3 if i == 24 else 0),
               'causes': [{'id': c, 'likely': True} for c in causes]}
        tests = [{'name': 'RungeKuttaFourth::integrate: convergence order',
                  'status': 'passed' if passed else 'failed', 'score': 1, 'max_score': 1,
                  'tags': ['RungeKuttaFourth::integrate']},
                 {'name': 'Cloth::initializeSpring: spring count', 'status': 'passed',
                  'tags': ['Cloth::initializeSpring']},
                 {'name': 'Cloth::computeSpringForce: one spring',
                  'status': 'failed' if causes else 'passed',
                  'tags': ['Cloth::computeSpringForce', *causes]}]
        if i == 1:  # a guess, as the grader's extra_data says it
            tests[2]['extra_data'] = {'causes': [{'id': 'spring-force-sign', 'likely': False}]}
        with open(os.path.join(folder, 'results.json'), 'w') as f:
            json.dump({'score': total, 'tests': tests}, f)
        with open(os.path.join(folder, 'report.md'), 'w') as f:
            f.write(f'# Grading report: {name}\n')
        with open(os.path.join(folder, 'row.json'), 'w') as f:
            json.dump(row, f)
        expected[name] = (total, verdict, causes, passed)
    # one a typo'd path became: not graded, apart from the statistics
    os.makedirs(os.path.join(subs, 'zz-typo'))
    folder = os.path.join(batch, 'zz-typo')
    os.makedirs(folder)
    with open(os.path.join(folder, 'results.json'), 'w') as f:
        json.dump({'score': 0, 'tests': []}, f)
    with open(os.path.join(folder, 'report.md'), 'w') as f:
        f.write('# Grading report: zz-typo\n')
    with open(os.path.join(folder, 'row.json'), 'w') as f:
        json.dump({'submission': 'zz-typo', 'dir': os.path.join(subs, 'zz-typo'), 'edition': 0,
                   'stub_scores': {}, 'stub_max': {}, 'total': 0.0, 'max': 0.0,
                   'verdict': 'not-gradable', 'isolation': '',
                   'problem': 'none of cloth.cpp, sphere.cpp, integrator.cpp found', 'seconds': 0.1,
                   'causes': []}, f)
    return expected


def shown_names(b):
    return b.js("return [...document.querySelectorAll('.cl-submissions tbody tr')]"
                ".map((tr) => tr.dataset.name)")


def main():
    options, checks = browser.start()
    with tempfile.TemporaryDirectory(prefix='clothref-class-test-') as tmp:
        batch, subs = os.path.join(tmp, 'batch'), os.path.join(tmp, 'subs')
        expected = fixture(batch, subs)
        names = sorted(expected)
        result = subprocess.run([options.cli, 'grade', '--out', batch,
                                 *[os.path.join(subs, n) for n in names + ['zz-typo']]],
                                capture_output=True, text=True)
        checks.check(result.returncode == 0, f'grade rebuilt the batch: {result.stderr.strip()}')
        page = os.path.join(batch, 'index.html')
        checks.check(os.path.isfile(page), 'index.html written from the markers')
        if not os.path.isfile(page):
            checks.finish()
        b = browser.Browser()
        try:
            started = time.monotonic()
            url = b.open(page)
            opened = time.monotonic() - started
            timing = b.js("return performance.getEntriesByType('navigation')[0].loadEventEnd")
            print(f'      30 submissions: {os.path.getsize(page) / 1e3:.1f} kB, load event at '
                  f'{timing:.0f} ms, driver.get {opened:.2f} s')
            checks.check(0 < timing < 2000, f'opens in under 2 s ({timing:.0f} ms)')
            checks.check(b.js("return document.getElementById('class').dataset.ready === '1'"),
                         'the page mounted')
            checks.check(shown_names(b) == names, 'all 30 rows, sorted by name')
            header = "[...document.querySelectorAll('.cl-submissions th')]" \
                     ".find((th) => th.textContent.startsWith(arguments[0])).click()"
            by_total = sorted(names, key=lambda n: (expected[n][0], n))
            b.js(header, 'total')
            checks.check(shown_names(b) == by_total, 'sorted by total, ascending')
            b.js(header, 'total')
            descending = sorted(names, key=lambda n: (-expected[n][0], n))
            checks.check(shown_names(b) == descending, 'sorted by total, descending')
            b.save_screenshot(os.path.join(options.screenshots, 'class-index.png'))
            set_filter = "const f = document.querySelector('.cl-filter'); f.value = arguments[0];" \
                         "f.dispatchEvent(new Event('input'));"
            b.js(set_filter, 'backup')
            with_cause = sorted(n for n in names if 'backup-aliases' in expected[n][2])
            checks.check(sorted(shown_names(b)) == with_cause and len(with_cause) == 14,
                         f'filter by cause: {len(shown_names(b))} rows')
            shown = b.js("return document.querySelector('.cl-shown').textContent")
            checks.check(shown == '14 of 30 shown', f'count of shown rows: {shown}')
            b.js(set_filter, 'compile-error')
            checks.check(sorted(shown_names(b)) == ['student03', 'student17'], 'filter by verdict')
            b.js(set_filter, '')
            checks.check(len(shown_names(b)) == 30, 'clearing the filter shows all')
            bars = b.js("return [...document.querySelectorAll('.cl-hist-bar')]"
                        ".map((r) => Number(r.dataset.count))")
            checks.check(len(bars) == 10 and sum(bars) == 30, f'histogram of 30 totals {bars}')
            labels = b.js("return [...document.querySelectorAll('.cl-hist-label')]"
                          ".map((t) => t.textContent)")
            checks.check(len(labels) == 10 and labels[0] == '0–8' and labels[-1] == '72–80',
                         f'the bins are labelled {labels}')
            axes = b.js("return [...document.querySelectorAll('.cl-hist text')]"
                        ".map((t) => t.textContent)")
            checks.check('submissions' in axes and 'total (points of 80)' in axes,
                         'the axes are labelled')
            apart = b.js("return [...document.querySelectorAll('.cl-apart tr[data-name]')]"
                         ".map((tr) => [tr.dataset.name, tr.cells[1].textContent])")
            checks.check(apart == [['zz-typo', 'not-gradable']], f'not graded, apart: {apart}')
            summary = b.js("return document.querySelector('.cl-summary').textContent")
            mean = sum(expected[n][0] for n in names) / 30
            checks.check(f'Mean total {round(mean * 1000) / 1000:g} / 80' in summary and
                         '1 not graded' in summary, f'the statistics leave it out: {summary}')
            # the first line: how many graded, how many need attention and why
            checks.check(summary.startswith('30 of 31 submissions graded; 4 need attention '
                                            '(2 compile-error, 1 not-gradable, 1 timed-out)'),
                         f'the first line says who needs attention and why: {summary}')
            isolation = b.js("return document.querySelector('.cl-isolation').textContent")
            checks.check(isolation == 'Student code ran with: rlimits only.',
                         f'the isolation, once: {isolation}')
            maxima = b.js("return [...document.querySelectorAll('.cl-submissions th')]"
                          ".map((th) => th.querySelector('.cl-max') ?"
                          " th.querySelector('.cl-max').textContent : null)")
            checks.check(maxima[1:9] == ['/10, 15', '/20, 25', '/10, 20', '/10', '/5', '/2.5',
                                         '/2.5', '/15'],
                         f'every stub column shows its maximum: {maxima}')
            cells = b.js("const tr = document.querySelector('.cl-submissions tr[data-name=\"student24\"]');"
                         "return [...tr.cells].map((td) => td.textContent)")
            checks.check(cells[3] == '20/20' and cells[4] == '' and cells[-1] == '51.1',
                         f'a 2024 row: its own maximum where the editions differ, seconds whole: {cells}')
            legend = b.js("const c = document.querySelector('.cl-submissions caption');"
                          "return c ? c.textContent : ''")
            checks.check('a guess' in legend and 'a likely cause' in legend,
                         f'the legend is the table\'s caption: {legend}')
            more = b.js("const m = document.querySelector('.cl-submissions tr[data-name=\"student04\"] .cl-more');"
                        "return m ? [m.textContent, m.title] : null")
            checks.check(more is not None and more[0] == '+2' and all(c in more[1] for c in LONG_CAUSES),
                         f'two chips, then a count whose tooltip lists them all: {more}')
            chips = b.js("return [...document.querySelectorAll('.cl-submissions tr[data-name=\"student01\"] .cl-chip')]"
                         ".map((c) => c.textContent)")
            checks.check(chips == ['spring-force-sign?'], f'a guess is a marked chip: {chips}')
            cause = b.js("const tr = document.querySelector('.cl-causes tr[data-cause=\"backup-aliases\"]');"
                         "return tr ? [tr.cells[1].textContent,"
                         " [...tr.querySelectorAll('a')].map((a) => a.getAttribute('href'))] : null")
            checks.check(cause is not None and cause[0] == '14' and
                         sorted(cause[1]) == [f'{n}/report.md' for n in with_cause] and
                         all(os.path.isfile(os.path.join(batch, h)) for h in cause[1]),
                         'backup-aliases: 14, linked to their reports')
            rate = b.js("const tr = [...document.querySelectorAll('.cl-check-rate tr')].find("
                        "(tr) => tr.cells[0].textContent.startsWith('RungeKuttaFourth'));"
                        "return tr ? tr.cells[1].textContent : null")
            passed = sum(1 for n in names if expected[n][3])
            checks.check(rate == f'{round(100 * passed / 30)} %', f'check pass rate {rate}')
            browser.check_quiet(b, checks, url, 'class')
        finally:
            b.close()
        for width in (1280, 1920):
            check_fits(page, width, checks, options.screenshots)
    checks.finish()


def check_fits(page, width, checks, screenshots):
    """At `width` px: no horizontal scrolling, every column of the table inside the window, no
    cell's text cut, every row at most two lines."""
    b = browser.Browser(width=width, height=900)
    try:
        b.open(page)
        scroll = b.js("return [document.documentElement.scrollWidth, window.innerWidth]")
        checks.check(scroll[0] <= scroll[1], f'{width} px: no horizontal scrolling {scroll}')
        columns = b.js("return [...document.querySelectorAll('.cl-submissions th')].map((th) => {"
                       " const r = th.getBoundingClientRect();"
                       " return [th.textContent, r.left, r.right, r.width]; })")
        outside = [c for c in columns if c[1] < 0 or c[2] > width or c[3] < 20]
        checks.check(len(columns) == 13 and not outside,
                     f'{width} px: all {len(columns)} columns visible ({outside})')
        # no text cut: every cell, header and chip is at least as wide as what it holds (an
        # ellipsis or a hidden overflow would show as content wider than the box)
        clipped = b.js("return [...document.querySelectorAll('.cl-submissions th,"
                       " .cl-submissions td, .cl-submissions .cl-chip, .cl-submissions .cl-more')]"
                       ".filter((e) => e.scrollWidth > e.clientWidth + 1"
                       " || getComputedStyle(e).textOverflow === 'ellipsis')"
                       ".map((e) => [e.textContent, e.scrollWidth, e.clientWidth])")
        checks.check(not clipped, f'{width} px: no cell\'s text is cut {clipped[:5]}')
        heights = b.js("return [...document.querySelectorAll('.cl-submissions tbody tr')]"
                       ".map((tr) => tr.getBoundingClientRect().height)")
        line = b.js("return parseFloat(getComputedStyle(document.querySelector("
                    "'.cl-submissions td')).lineHeight) || 20")
        checks.check(heights and max(heights) < 3 * line,
                     f'{width} px: every row at most two lines (tallest {max(heights):.0f} px, line {line:.0f} px)')
        b.save_screenshot(os.path.join(screenshots, f'class-index-{width}.png'))
    finally:
        b.close()


if __name__ == '__main__':
    main()
