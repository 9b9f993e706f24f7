'use strict';
// The class overview (BATCHDIR/index.html, docs/pictures.md): a first line saying how many were
// graded and how many need attention and why; a sortable, filterable table of submissions that
// fits the window with nothing cut (at 1280 px every column is in the window, every number whole,
// cause chips whole: two, then a count, the full list on hover), its legend in its caption; a
// labelled histogram of totals, pass rates per stub and per check, and the named causes with links
// to the reports that show them. Submissions the grader could not grade are listed apart and left
// out of every statistic. Text from submissions is set with textContent only.

function mountClass(root, data) {
  const all = data.submissions;
  // not graded at all (the grader refused the folder, or failed itself): apart from the statistics
  const apart = all.filter((s) => s.verdict === 'not-gradable' || s.verdict === 'grader-error');
  const subs = all.filter((s) => !apart.includes(s));
  function element(tag, className, text) {
    const e = document.createElement(tag);
    if (className) e.className = className;
    if (text !== undefined) e.textContent = text;
    return e;
  }
  // points as every output shows them: rounded to 0.001, no trailing zeros
  const fmt = (v) => String(Math.round(v * 1000) / 1000);
  const link = (s) => {
    const a = element('a', null, s.submission);
    a.href = s.report.split('/').map(encodeURIComponent).join('/');
    return a;
  };
  const stubs = data.stubs.filter((stub) => subs.some((s) => stub in s.stub_max));
  const shortName = {
    'Cloth::initializeSpring': 'springs', 'Cloth::computeSpringForce': 'forces',
    'Spheres::collide(Cloth*)': 'collide (Cloth*)', 'Spheres::collide()': 'collide ()',
    // soft hyphens: a narrow column breaks the name where a reader expects it
    'ExplicitEuler::integrate': 'Ex\u00adplicit', 'ImplicitEuler::integrate': 'Im\u00adplicit',
    'MidpointEuler::integrate': 'Mid\u00adpoint', 'RungeKuttaFourth::integrate': 'RK4',
  };
  const svgNs = 'http://www.w3.org/2000/svg';
  function svg(tag, attributes, text) {
    const e = document.createElementNS(svgNs, tag);
    for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  }

  // ---- summary and histogram (graded submissions only)
  const totals = subs.map((s) => s.total).sort((a, b) => a - b);
  const mean = totals.length ? totals.reduce((sum, t) => sum + t, 0) / totals.length : 0;
  const median = totals.length ? (totals[(totals.length - 1) >> 1] + totals[totals.length >> 1]) / 2 : 0;
  const maxTotal = Math.max(1, ...subs.map((s) => s.max || 0));
  // the first line: how many were graded, how many need attention and why (their verdicts)
  const attention = all.filter((s) => s.verdict !== 'graded');
  const verdicts = new Map();
  for (const s of attention) verdicts.set(s.verdict, (verdicts.get(s.verdict) || 0) + 1);
  const why = [...verdicts].sort((a, b) => b[1] - a[1] || a[0].localeCompare(b[0]))
      .map(([verdict, count]) => `${count} ${verdict}`).join(', ');
  root.appendChild(element('p', 'cl-summary',
      `${subs.length} of ${all.length} submissions graded; ` +
      (attention.length ? `${attention.length} need attention (${why}): their reports say what ` +
                          'went wrong' : 'none needs attention') +
      (apart.length ? `; ${apart.length} not graded, listed apart below and left out of the ` +
                      'statistics' : '') +
      `. Mean total ${fmt(mean)} / ${fmt(maxTotal)}, median ${fmt(median)}.`));
  if (data.isolation && data.isolation.length)
    root.appendChild(element('p', 'cl-isolation', `Student code ran with: ${data.isolation.join('; ')}.`));
  root.appendChild(element('h2', null, 'Totals'));
  const bins = new Array(10).fill(0);
  for (const s of subs) bins[Math.min(9, Math.floor((10 * Math.max(0, s.total)) / maxTotal))]++;
  const left = 44, bottom = 150, barWidth = 56, gap = 4, height = 110;
  const hist = svg('svg', {class: 'cl-hist', width: left + 10 * (barWidth + gap) + 20, height: 196,
                           role: 'img', 'aria-label': 'histogram of totals'});
  const top = Math.max(1, ...bins);
  hist.appendChild(svg('line', {x1: left, y1: bottom, x2: left + 10 * (barWidth + gap), y2: bottom,
                                stroke: '#888'}));
  bins.forEach((count, i) => {
    const h = (height * count) / top;
    const x = left + i * (barWidth + gap);
    const bar = svg('rect', {x, y: bottom - h, width: barWidth, height: h, fill: '#4a7fb5',
                             class: 'cl-hist-bar'});
    bar.dataset.count = count;
    const lo = (i * maxTotal) / 10, hi = ((i + 1) * maxTotal) / 10;
    bar.appendChild(svg('title', {}, `${count} with total in [${fmt(lo)}, ${fmt(hi)}${i === 9 ? ']' : ')'}`));
    hist.appendChild(bar);
    hist.appendChild(svg('text', {x: x + barWidth / 2, y: bottom - h - 4, 'text-anchor': 'middle',
                                  'font-size': 11, class: 'cl-hist-count'}, count ? String(count) : ''));
    hist.appendChild(svg('text', {x: x + barWidth / 2, y: bottom + 14, 'text-anchor': 'middle',
                                  'font-size': 10, class: 'cl-hist-label'},
                         `${fmt(lo)}–${fmt(hi)}`));
  });
  hist.appendChild(svg('text', {x: left + 5 * (barWidth + gap), y: bottom + 34, 'text-anchor': 'middle',
                                'font-size': 11}, `total (points of ${fmt(maxTotal)})`));
  hist.appendChild(svg('text', {x: 12, y: bottom - height / 2, 'text-anchor': 'middle', 'font-size': 11,
                                transform: `rotate(-90 12 ${bottom - height / 2})`}, 'submissions'));
  root.appendChild(hist);

  // ---- the table
  root.appendChild(element('h2', null, 'Submissions'));
  const filter = element('input', 'cl-filter');
  filter.type = 'search';
  filter.placeholder = 'filter: name, verdict or cause';
  const shownCount = element('span', 'cl-shown');
  root.append(filter, ' ', shownCount);
  // the maxima of a stub's column, ascending: one when every submission has the same
  const maximaOf = (stub) => [...new Set(subs.filter((s) => stub in s.stub_max)
                                             .map((s) => s.stub_max[stub]))].sort((a, b) => a - b);
  const causeText = (s) => s.causes.map((c) => c.id + (c.likely ? '' : '?')).join(', ');
  function chips(s) {
    const td = element('td', 'cl-causes-cell');
    td.title = causeText(s);
    s.causes.slice(0, 2).forEach((c) => {
      const chip = element('span', 'cl-chip' + (c.likely ? '' : ' cl-guess'), c.id + (c.likely ? '' : '?'));
      chip.dataset.cause = c.id;
      td.appendChild(chip);
    });
    if (s.causes.length > 2) {
      const more = element('span', 'cl-more', `+${s.causes.length - 2}`);
      more.title = causeText(s);
      td.appendChild(more);
    }
    return td;
  }
  const columns = [
    {title: 'submission', cls: 'cl-name', value: (s) => s.submission,
     cell: (s) => { const td = element('td', 'cl-name'); td.appendChild(link(s)); return td; }},
    ...stubs.map((stub) => {
      const maxima = maximaOf(stub);
      return {
        title: shortName[stub] || stub, full: stub, max: maxima.map(fmt).join(', '), cls: 'cl-num',
        value: (s) => (stub in s.stub_scores ? s.stub_scores[stub] : -1),
        cell: (s) => {
          if (!(stub in s.stub_scores)) return element('td', 'cl-num');
          const got = s.stub_scores[stub], max = s.stub_max[stub];
          const td = element('td', 'cl-num' + (got >= max ? ' cl-full' : got === 0 && max > 0 ? ' cl-none' : ''),
                             maxima.length === 1 ? fmt(got) : `${fmt(got)}/${fmt(max)}`);
          td.title = `${stub}: ${fmt(got)} / ${fmt(max)}`;
          return td;
        },
      };
    }),
    {title: 'total', cls: 'cl-num', value: (s) => s.total,
     cell: (s) => element('td', 'cl-num', `${fmt(s.total)} / ${fmt(s.max)}`)},
    {title: 'verdict', cls: 'cl-verdict', value: (s) => s.verdict,
     cell: (s) => element('td', 'cl-verdict' + (s.verdict === 'graded' ? '' : ' cl-verdict-bad'), s.verdict)},
    {title: 'causes', cls: 'cl-causes-cell', value: (s) => causeText(s), cell: chips},
    {title: 's', full: 'seconds of grading', cls: 'cl-num', value: (s) => s.seconds,
     cell: (s) => element('td', 'cl-num', s.seconds.toFixed(1))},
  ];
  const table = element('table', 'cl-table cl-submissions');
  // the legend, in the table's caption: right above its header, never a footnote
  const legend = element('caption', 'cl-legend');
  const key = (className, text, what) => {
    const item = element('span', 'cl-key');
    item.append(element('span', className, text), ` ${what}`);
    return item;
  };
  legend.append(
      key('cl-chip', 'id', 'a likely cause'), key('cl-chip cl-guess', 'id?', 'a guess'),
      key('cl-more', '+n', 'more causes (all on hover and in the report)'),
      key('cl-full', '5', 'full points'), key('cl-none', '0', 'none'),
      key('cl-max', '/5', 'the stub\'s maximum (two when the editions differ: each cell then says its own)'),
      element('span', 'cl-key', 's: seconds of grading'));
  table.appendChild(legend);
  const head = table.createTHead().insertRow();
  const body = table.createTBody();
  let sortColumn = 0, sortUp = true;
  function render() {
    const needle = filter.value.trim().toLowerCase();
    const rows = subs.filter((s) => !needle ||
        [s.submission, s.verdict, ...s.causes.map((c) => c.id)].some((text) => text.toLowerCase().includes(needle)));
    const value = columns[sortColumn].value;
    rows.sort((a, b) => {
      const x = value(a), y = value(b);
      const order = typeof x === 'number' ? x - y : String(x).localeCompare(String(y));
      return (sortUp ? order : -order) || a.submission.localeCompare(b.submission);
    });
    body.replaceChildren();
    for (const s of rows) {
      const tr = body.insertRow();
      tr.dataset.name = s.submission;
      for (const c of columns) tr.appendChild(c.cell(s));
    }
    head.querySelectorAll('th').forEach((th, i) => {
      th.classList.toggle('cl-sorted-up', i === sortColumn && sortUp);
      th.classList.toggle('cl-sorted-down', i === sortColumn && !sortUp);
    });
    shownCount.textContent = `${rows.length} of ${subs.length} shown`;
  }
  columns.forEach((c, i) => {
    const th = element('th', c.cls, c.title);
    th.title = c.full || c.title;
    if (c.max !== undefined) {
      th.appendChild(document.createElement('br'));
      th.appendChild(element('span', 'cl-max', `/${c.max}`));
    }
    th.addEventListener('click', () => {
      sortUp = sortColumn === i ? !sortUp : true;
      sortColumn = i;
      render();
    });
    head.appendChild(th);
  });
  filter.addEventListener('input', render);
  root.appendChild(table);
  render();

  // ---- not graded: apart, with why
  if (apart.length) {
    root.appendChild(element('h2', null, `Not graded (${apart.length})`));
    const t = element('table', 'cl-table cl-apart');
    const h = t.createTHead().insertRow();
    for (const text of ['submission', 'verdict', 'why']) h.appendChild(element('th', null, text));
    for (const s of apart) {
      const tr = t.insertRow();
      tr.dataset.name = s.submission;
      tr.insertCell().appendChild(link(s));
      tr.insertCell().textContent = s.verdict;
      tr.insertCell().textContent = s.problem || '';
    }
    root.appendChild(t);
  }

  // ---- pass rates
  function rateTable(title, rows, className) {
    root.appendChild(element('h2', null, title));
    const t = element('table', 'cl-table cl-rate ' + className);
    const h = t.createTHead().insertRow();
    for (const text of ['', 'rate', '', 'of']) h.appendChild(element('th', null, text));
    for (const [name, rate, of] of rows) {
      const tr = t.insertRow();
      tr.insertCell().textContent = name;
      tr.insertCell().textContent = of ? `${Math.round(100 * rate)} %` : '';
      const bar = element('span', 'cl-bar');
      bar.style.width = `${Math.round(100 * rate)}px`;
      tr.insertCell().appendChild(bar);
      tr.insertCell().textContent = String(of);
    }
    root.appendChild(t);
  }
  rateTable('Score rate per stub', stubs.map((stub) => {
    const having = subs.filter((s) => stub in s.stub_max && s.stub_max[stub] > 0);
    const got = having.reduce((sum, s) => sum + s.stub_scores[stub] / s.stub_max[stub], 0);
    return [stub, having.length ? got / having.length : 0, having.length];
  }), 'cl-stub-rate');
  rateTable('Pass rate per check', data.checks.map((check, i) => {
    const having = subs.filter((s) => String(i) in s.checks);
    const passed = having.filter((s) => s.checks[String(i)]).length;
    return [check, having.length ? passed / having.length : 0, having.length];
  }), 'cl-check-rate');

  // ---- named causes
  root.appendChild(element('h2', null, 'Named causes'));
  const named = new Map();
  for (const s of subs)
    for (const c of s.causes) named.set(c.id, [...(named.get(c.id) || []), s]);
  const list = element('table', 'cl-table cl-causes');
  const ch = list.createTHead().insertRow();
  for (const text of ['cause', 'submissions', 'reports']) ch.appendChild(element('th', null, text));
  for (const [cause, who] of [...named].sort((a, b) => b[1].length - a[1].length ||
                                                     a[0].localeCompare(b[0]))) {
    const tr = list.insertRow();
    tr.dataset.cause = cause;
    tr.insertCell().textContent = cause;
    tr.insertCell().textContent = String(who.length);
    const links = tr.insertCell();
    links.style.textAlign = 'left';
    who.forEach((s, k) => {
      if (k) links.append(', ');
      links.appendChild(link(s));
    });
  }
  if (named.size === 0) root.appendChild(element('p', null, 'No named cause in this batch.'));
  else root.appendChild(list);
  root.dataset.ready = '1';
}
