import * as assert from 'node:assert/strict';
import { XMLValidator } from 'fast-xml-parser';
import {
  csvRecords,
  defaultAxes,
  filterRows,
  outcomeCounts,
  parseResultsCsv,
  ResultsCsvError,
  resultsReportHtml,
  scatterModel,
  scatterSvg,
  sortRows,
  tableHtml,
} from '../../common/src/variationsReport';
import { variationsHtml } from '../../client/src/variations/page';

const HEADER = 'index,status,collision,min_distance_m,min_ttc_s,end_time_s';
const CSV = [
  `${HEADER},EgoSpeed,Weather`,
  '0,ok,false,12.500,3.000,3.050,10,dry',
  '1,ok,true,0.000,0.000,3.050,20,wet',
  '2,timeout,false,,,30.000,30,dry',
  '3,error,false,,,0.000,5,"snow, heavy"',
  '10,ok,false,2.000,,3.050,15,wet',
  '',
].join('\n');
const STYLE = { width: 600, height: 300, foreground: '#000', grid: '#ccc', fontFamily: 'sans-serif' };

describe('variations: the results table, its sorting, filtering and scatter', () => {
  const table = parseResultsCsv(CSV);
  const indices = (rows: { index: string }[]) => rows.map((row) => row.index);

  it('reads results.csv: columns, parameters, outcomes (a collision wins over ok), quoted fields; a cut-off last line is left out', () => {
    assert.deepEqual(table.parameters, ['EgoSpeed', 'Weather']);
    assert.deepEqual(indices(table.rows), ['0', '1', '2', '3', '10']);
    assert.deepEqual(
      table.rows.map((row) => row.outcome),
      ['ok', 'collision', 'timeout', 'error', 'ok'],
    );
    assert.equal(table.rows[3].cells.Weather, 'snow, heavy');
    assert.deepEqual(outcomeCounts(table.rows), { ok: 2, limit: 0, collision: 1, timeout: 1, error: 1, discarded: 0 });
    assert.equal(
      parseResultsCsv(`${HEADER}\n4,limit,false,,,30.000\n`).rows[0].outcome,
      'limit',
      'a run stopped at the limit set is no ok',
    );
    assert.equal(parseResultsCsv(CSV + '11,ok,fal').rows.length, 5, 'a row still being written is not read');
    assert.deepEqual(csvRecords('a,"b ""c""",d\r\n'), [['a', 'b "c"', 'd']]);
    const withReason = parseResultsCsv(
      `${HEADER},EgoSpeed,reason\n0,error,false,,,,10,"esmini did not run the scenario (exit code 255): Failed to locate OpenDRIVE file e6mini.xodr"\n`,
    );
    assert.deepEqual(withReason.parameters, ['EgoSpeed'], 'the reason column after the parameters is none of them');
    assert.equal(
      withReason.rows[0].cells.reason,
      'esmini did not run the scenario (exit code 255): Failed to locate OpenDRIVE file e6mini.xodr',
    );
    assert.match(
      tableHtml(withReason.columns, withReason.rows),
      /<td[^>]*>esmini did not run the scenario \(exit code 255\): Failed to locate OpenDRIVE file e6mini\.xodr<\/td>/,
    );
    assert.throws(() => parseResultsCsv('x,y\n1,2\n'), ResultsCsvError);
    assert.throws(() => parseResultsCsv(''), ResultsCsvError);
  });

  it('sorts numbers as numbers, text naturally, empty cells last in both directions, ties by index', () => {
    assert.deepEqual(indices(sortRows(table.rows, { column: 'index', direction: 'ascending' })), ['0', '1', '2', '3', '10']);
    assert.deepEqual(indices(sortRows(table.rows, { column: 'index', direction: 'descending' })), ['10', '3', '2', '1', '0']);
    assert.deepEqual(indices(sortRows(table.rows, { column: 'min_distance_m', direction: 'ascending' })), ['1', '10', '0', '2', '3']);
    assert.deepEqual(indices(sortRows(table.rows, { column: 'min_distance_m', direction: 'descending' })), ['0', '10', '1', '2', '3']);
    assert.deepEqual(indices(sortRows(table.rows, { column: 'Weather', direction: 'ascending' })), ['0', '2', '3', '1', '10']);
    assert.deepEqual(indices(sortRows(table.rows, { column: 'status', direction: 'descending' })), ['2', '0', '1', '10', '3']);
  });

  it('filters by outcome', () => {
    assert.deepEqual(indices(filterRows(table.rows, new Set(['collision', 'error']))), ['1', '3']);
    assert.deepEqual(filterRows(table.rows, new Set()), []);
    assert.equal(filterRows(table.rows, new Set(['ok', 'collision', 'timeout', 'error'])).length, 5);
  });

  it('the scatter: numeric axes scaled to 0..1 with round ticks, text as categories, rows without a value left out', () => {
    const numeric = scatterModel(table.rows, 'EgoSpeed', 'min_distance_m');
    assert.equal(numeric.x.kind, 'number');
    assert.equal(numeric.omitted, 2, 'rows 2 and 3 have no distance');
    assert.deepEqual(indices(numeric.points), ['0', '1', '10']);
    const [zero, one] = numeric.points;
    assert.equal(zero.x, (10 - 5) / 25);
    assert.equal(zero.y, 1);
    assert.equal(one.y, 0);
    assert.deepEqual(
      numeric.x.ticks.map((tick) => tick.label),
      ['5', '10', '15', '20', '25', '30'],
    );
    for (const tick of [...numeric.x.ticks, ...numeric.y.ticks]) assert.ok(tick.at >= 0 && tick.at <= 1, `${tick.label} at ${tick.at}`);
    const category = scatterModel(table.rows, 'Weather', 'EgoSpeed');
    assert.equal(category.x.kind, 'category');
    assert.deepEqual(
      category.x.ticks.map((tick) => [tick.label, tick.at]),
      [
        ['dry', 0],
        ['snow, heavy', 0.5],
        ['wet', 1],
      ],
    );
    assert.equal(category.points.length, 5);
    const single = scatterModel(table.rows.slice(0, 1), 'EgoSpeed', 'EgoSpeed');
    assert.equal(single.points[0].x, 0.5, 'one value stands in the middle');
    assert.deepEqual(defaultAxes(table), { x: 'EgoSpeed', y: 'Weather' });
    assert.deepEqual(defaultAxes(parseResultsCsv(`${HEADER},A\n0,ok,false,1,1,1,2\n`)), { x: 'A', y: 'min_distance_m' });
  });

  it('the scatter as SVG: a circle per point coloured by outcome, labelled axes and a legend; well-formed', () => {
    const svg = scatterSvg(scatterModel(table.rows, 'EgoSpeed', 'Weather'), STYLE);
    assert.equal(XMLValidator.validate(svg), true);
    assert.equal((svg.match(/<circle class="point"/g) ?? []).length, 5);
    assert.match(svg, /data-index="1"[^>]*fill="#d55e00"/, 'the collision in the collision colour');
    assert.match(svg, />EgoSpeed<\/text>/);
    assert.match(svg, />collision \(1\)<\/text>/);
    assert.match(svg, />snow, heavy<\/text>/);
    // Runs 0 and 1 differ only in C: at the same A and B, they are set apart.
    const twins = parseResultsCsv(`${HEADER},A,B,C\n0,ok,false,1,1,1,1,1,1\n1,ok,true,1,1,1,1,1,2\n2,ok,false,1,1,1,2,2,1\n`);
    const places = [
      ...scatterSvg(scatterModel(twins.rows, 'A', 'B'), STYLE).matchAll(
        /<circle class="point" data-index="(\d)" cx="([\d.]+)" cy="([\d.]+)"/g,
      ),
    ].map((match) => `${match[2]},${match[3]}`);
    assert.equal(places.length, 3);
    assert.equal(new Set(places).size, 3, `each run has a place of its own: ${places.join(' ')}`);
  });

  it('the table as HTML: the sort marked on its header, a row per result, escaped; in the view the headers sort buttons and the index a link', () => {
    const rows = sortRows(table.rows, { column: 'EgoSpeed', direction: 'descending' });
    const html = tableHtml(table.columns, rows, { column: 'EgoSpeed', direction: 'descending' }, true);
    assert.equal(XMLValidator.validate(html), true);
    assert.match(html, /<th data-column="EgoSpeed" aria-sort="descending"><button class="sort"[^>]*>EgoSpeed ▼<\/button><\/th>/);
    assert.match(
      tableHtml(table.columns, rows, { column: 'EgoSpeed', direction: 'descending' }),
      /<th data-column="EgoSpeed" aria-sort="descending">EgoSpeed ▼<\/th>/,
      'the report: no buttons',
    );
    assert.deepEqual(
      [...html.matchAll(/<tr class="\w+" data-index="(\d+)">/g)].map((match) => match[1]),
      ['2', '1', '10', '0', '3'],
    );
    assert.match(html, /<a href="#" class="open"[^>]*>#3<\/a>/);
    assert.doesNotMatch(tableHtml(table.columns, rows), /<a |<button/);
    assert.match(tableHtml(['index', 'x'], [{ index: '0', outcome: 'ok', cells: { index: '0', x: '<b>&' } }]), /<td>&lt;b&gt;&amp;<\/td>/);
  });

  it('the table as HTML: the run last opened is marked selected, and only it, so the page can show it', () => {
    const rows = sortRows(table.rows, { column: 'index', direction: 'ascending' });
    const html = tableHtml(table.columns, rows, { column: 'index', direction: 'ascending' }, true, '10');
    assert.equal(XMLValidator.validate(html), true);
    assert.deepEqual(
      [...html.matchAll(/<tr class="[\w ]*\bselected" aria-selected="true" data-index="(\d+)">/g)].map((match) => match[1]),
      ['10'],
    );
    assert.equal([...html.matchAll(/selected/g)].length, 2, 'the class and aria-selected of one row');
    assert.doesNotMatch(tableHtml(table.columns, rows, undefined, true), /selected/);
    assert.doesNotMatch(tableHtml(table.columns, rows, undefined, true, '99'), /selected/, 'a run not in the table marks nothing');
  });

  it('the page shows the selected row while the pointer still rests on it (hover does not hide it)', () => {
    const html = variationsHtml('csp', 'script.js', 'nonce');
    const style = /<style>([\s\S]*)<\/style>/.exec(html)?.[1] ?? '';
    const rule = /([^{}]*tr\.selected:hover[^{}]*)\{([^}]*)\}/.exec(style);
    assert.ok(rule, 'a rule for the selected row under the pointer');
    assert.match(rule[1], /tbody tr\.selected,/, 'the same rule as without the pointer');
    assert.match(rule[2], /background:var\(--vscode-list-activeSelectionBackground,#[0-9a-f]+\)/, 'with a colour when the theme has none');
    assert.match(rule[2], /outline:/);
    assert.match(html, /<div id="notice" role="status"><\/div>/, 'a place for why a click opened nothing');
  });

  it('the first axes are never an empty column, and long category labels do not overlap', () => {
    const noTtc = parseResultsCsv(
      `${HEADER},Road\n0,ok,false,,,40.000,./road_networks/alks_road_left_radius_250m.xodr\n1,ok,false,,,50.000,./road_networks/alks_road_right_radius_1000m.xodr\n2,ok,false,,,55.000,./road_networks/alks_road_straight.xodr\n`,
    );
    assert.deepEqual(defaultAxes(noTtc), { x: 'Road', y: 'end_time_s' }, 'min_distance_m and min_ttc_s are empty in every row');
    const svg = scatterSvg(scatterModel(noTtc.rows, 'Road', 'end_time_s'), { ...STYLE, width: 360 });
    const labels = [...svg.matchAll(/<text x="([\d.]+)" y="[\d.]+" text-anchor="middle"[^>]*><title>[^<]*<\/title>([^<]*)<\/text>/g)].map(
      (match) => ({
        x: Number(match[1]),
        width: match[2].length * 6.5,
      }),
    );
    assert.ok(labels.length >= 1);
    for (let i = 1; i < labels.length; i++)
      assert.ok(labels[i].x - labels[i].width / 2 >= labels[i - 1].x + labels[i - 1].width / 2, 'x labels apart');
    assert.match(svg, /<title>\.\/road_networks\/alks_road_left_radius_250m\.xodr<\/title>/, 'the whole label in its title');
  });

  it('the report: a whole document, every row, no script or outside resource', () => {
    const html = resultsReportHtml(table, 'Variations of d.xosc <1>');
    assert.equal(XMLValidator.validate(html.replace(/^<!DOCTYPE html>\n/, '')), true);
    assert.match(html, /<title>Variations of d\.xosc &lt;1&gt;<\/title>/);
    assert.equal((html.match(/<tr class=/g) ?? []).length, 5);
    assert.match(
      html,
      /5 runs: 2 ok, 0 limit, 1 collision \(esmini logged one; the status column says how each run ended\), 1 timeout, 1 error, 0 discarded/,
    );
    assert.doesNotMatch(html, /<script|src=/);
  });
});
