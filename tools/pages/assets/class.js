'use strict';
// The class overview (BATCHDIR/index.html, docs/pictures.md): a sortable, filterable table of
// submissions, a histogram of totals, pass rates per stub and per check, and the named causes with
// links to the reports that show them. Text from submissions is set with textContent only.

function mountClass(root, data) {
  const subs = data.submissions;
  function element(tag, className, text) {
    const e = document.createElement(tag);
    if (className) e.className = className;
    if (text !== undefined) e.textContent = text;
    return e;
  }
  const fmt = (v) => (Math.round(v * 100) / 100).toString();
  const link = (s) => {
    const a = element('a', null, s.submission);
    a.href = s.report.split('/').map(encodeURIComponent).join('/');
    return a;
  };
  const stubs = data.stubs.filter((stub) => subs.some((s) => stub in s.stub_max));

  // ---- summary and histogram
  const graded = subs.filter((s) => s.verdict === 'graded');
  const mean = subs.length ? subs.reduce((sum, s) => sum + s.total, 0) / subs.length : 0;
  root.appendChild(element('p', 'cl-summary',
      `${subs.length} submissions, ${graded.length} graded without trouble; mean total ${fmt(mean)}.`));
  root.appendChild(element('h2', null, 'Totals'));
  const maxTotal = Math.max(1, ...subs.map((s) => s.max || 0));
  const bins = new Array(10).fill(0);
  for (const s of subs) bins[Math.min(9, Math.floor((10 * Math.max(0, s.total)) / maxTotal))]++;
  const svgNs = 'http://www.w3.org/2000/svg';
  const hist = document.createElementNS(svgNs, 'svg');
  hist.setAttribute('class', 'cl-hist');
  hist.setAttribute('width', '520');
  hist.setAttribute('height', '150');
  const top = Math.max(1, ...bins);
  bins.forEach((count, i) => {
    const h = (100 * count) / top;
    const bar = document.createElementNS(svgNs, 'rect');
    bar.setAttribute('x', 40 + i * 47);
    bar.setAttribute('y', 120 - h);
    bar.setAttribute('width', 43);
    bar.setAttribute('height', h);
    bar.setAttribute('fill', '#4a7fb5');
    bar.setAttribute('class', 'cl-hist-bar');
    bar.dataset.count = count;
    const title = document.createElementNS(svgNs, 'title');
    title.textContent = `${count} with total in [${fmt((i * maxTotal) / 10)}, ${fmt(((i + 1) * maxTotal) / 10)})`;
    bar.appendChild(title);
    hist.appendChild(bar);
    const label = document.createElementNS(svgNs, 'text');
    label.setAttribute('x', 40 + i * 47 + 21);
    label.setAttribute('y', 115 - h);
    label.setAttribute('text-anchor', 'middle');
    label.setAttribute('font-size', '11');
    label.textContent = count ? String(count) : '';
    hist.appendChild(label);
  });
  for (const [x, text] of [[40, '0'], [510, fmt(maxTotal)]]) {
    const t = document.createElementNS(svgNs, 'text');
    t.setAttribute('x', x);
    t.setAttribute('y', 138);
    t.setAttribute('font-size', '11');
    t.setAttribute('text-anchor', x > 40 ? 'end' : 'start');
    t.textContent = text;
    hist.appendChild(t);
  }
  root.appendChild(hist);

  // ---- the table
  root.appendChild(element('h2', null, 'Submissions'));
  const filter = element('input', 'cl-filter');
  filter.type = 'search';
  filter.placeholder = 'filter: name, verdict or cause';
  const shownCount = element('span', 'cl-shown');
  root.append(filter, ' ', shownCount);
  const columns = [
    {title: 'submission', value: (s) => s.submission, cell: (s) => link(s)},
    ...stubs.map((stub) => ({
      title: stub,
      value: (s) => (stub in s.stub_scores ? s.stub_scores[stub] : -1),
      cell: (s) => (stub in s.stub_scores ? `${fmt(s.stub_scores[stub])} / ${fmt(s.stub_max[stub])}` : ''),
    })),
    {title: 'total', value: (s) => s.total, cell: (s) => `${fmt(s.total)} / ${fmt(s.max)}`},
    {title: 'verdict', value: (s) => s.verdict, cell: (s) => s.verdict},
    {title: 'causes', value: (s) => s.causes.join(' '), cell: (s) => s.causes.join(', ')},
    {title: 'seconds', value: (s) => s.seconds, cell: (s) => s.seconds.toFixed(1)},
  ];
  const table = element('table', 'cl-table cl-submissions');
  const head = table.createTHead().insertRow();
  const body = table.createTBody();
  let sortColumn = 0, sortUp = true;
  function render() {
    const needle = filter.value.trim().toLowerCase();
    const rows = subs.filter((s) => !needle ||
        [s.submission, s.verdict, ...s.causes].some((text) => text.toLowerCase().includes(needle)));
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
      for (const c of columns) {
        const td = tr.insertCell();
        const content = c.cell(s);
        if (typeof content === 'string') td.textContent = content;
        else td.appendChild(content);
      }
      if (s.verdict !== 'graded') tr.cells[columns.length - 3].className = 'cl-verdict-bad';
    }
    head.querySelectorAll('th').forEach((th, i) => {
      th.className = i === sortColumn ? (sortUp ? 'cl-sorted-up' : 'cl-sorted-down') : '';
    });
    shownCount.textContent = `${rows.length} of ${subs.length} shown`;
  }
  columns.forEach((c, i) => {
    const th = element('th', null, c.title);
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
  const causes = new Map();
  for (const s of subs)
    for (const c of s.causes) causes.set(c, [...(causes.get(c) || []), s]);
  const list = element('table', 'cl-table cl-causes');
  const ch = list.createTHead().insertRow();
  for (const text of ['cause', 'submissions', 'reports']) ch.appendChild(element('th', null, text));
  for (const [cause, who] of [...causes].sort((a, b) => b[1].length - a[1].length ||
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
  if (causes.size === 0) root.appendChild(element('p', null, 'No named cause in this batch.'));
  else root.appendChild(list);
  root.dataset.ready = '1';
}
