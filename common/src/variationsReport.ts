/**
 * A batch's results as a person reads them: results.csv as a table (sorted, filtered by outcome) and a scatter
 * plot of two columns coloured by outcome, rendered as HTML and SVG text. Pure: the Variations webview and the
 * self-contained results.html that `batch` writes both draw with it.
 */

/** What happened in a run, as the view colours and filters it: a collision wins over the status; `discarded` never ran (ValueConstraintGroups). */
export type Outcome = 'ok' | 'limit' | 'error' | 'timeout' | 'collision' | 'discarded';
export const OUTCOMES: readonly Outcome[] = ['ok', 'limit', 'collision', 'timeout', 'error', 'discarded'];
/** Colours distinguishable on dark and light themes and by most colour-blind readers (Okabe-Ito, and a neutral grey for what did not run). */
export const OUTCOME_COLORS: Record<Outcome, string> = {
  ok: '#009e73',
  limit: '#56b4e9',
  collision: '#d55e00',
  timeout: '#e69f00',
  error: '#cc79a7',
  discarded: '#999999',
};

/** The columns every results.csv starts with; the varied parameters follow. */
export const RESULT_COLUMNS = ['index', 'status', 'collision', 'min_distance_m', 'min_ttc_s', 'end_time_s'] as const;

/** The column `batch --fail-if` writes after the fixed ones: pass, fail, or empty. */
export const VERDICT_COLUMN = 'verdict';

/** The last column, after the parameters: why a run is not ok (esmini's reason for an error), empty when it is. */
export const REASON_COLUMN = 'reason';

export interface ResultRow {
  /** The concrete scenario's index (as esmini's --param_permutation). */
  index: string;
  outcome: Outcome;
  /** Every column's text, by column name. */
  cells: Record<string, string>;
}

export interface ResultsTable {
  columns: string[];
  /** The columns after the fixed ones (and before `reason`): one per varied parameter. */
  parameters: string[];
  rows: ResultRow[];
}

export class ResultsCsvError extends Error {}

/** Splits RFC 4180 CSV text into records of fields; a record cut short at the end (a batch still writing) is dropped. */
export function csvRecords(text: string): string[][] {
  const records: string[][] = [];
  let fields: string[] = [];
  let field = '';
  let quoted = false;
  let i = 0;
  while (i < text.length) {
    const char = text[i];
    if (quoted) {
      if (char === '"' && text[i + 1] === '"') {
        field += '"';
        i += 2;
        continue;
      }
      if (char === '"') quoted = false;
      else field += char;
      i++;
      continue;
    }
    if (char === '"') quoted = true;
    else if (char === ',') {
      fields.push(field);
      field = '';
    } else if (char === '\n') {
      fields.push(field.endsWith('\r') ? field.slice(0, -1) : field);
      records.push(fields);
      fields = [];
      field = '';
    } else field += char;
    i++;
  }
  return records;
}

export function outcomeOf(status: string, collision: string): Outcome {
  if (collision === 'true') return 'collision';
  return status === 'error' || status === 'timeout' || status === 'limit' || status === 'discarded' ? status : 'ok';
}

/** results.csv as a table; throws ResultsCsvError when it is not one (no header, or not the batch's columns). */
export function parseResultsCsv(text: string): ResultsTable {
  const records = csvRecords(text.startsWith('\ufeff') ? text.slice(1) : text);
  const header = records.shift();
  if (!header || RESULT_COLUMNS.some((column, i) => header[i] !== column)) {
    throw new ResultsCsvError(`not a batch's results.csv: its first line is not ${RESULT_COLUMNS.join(',')},…`);
  }
  const rows: ResultRow[] = [];
  for (const record of records) {
    if (record.length !== header.length) continue;
    const cells: Record<string, string> = {};
    header.forEach((column, i) => (cells[column] = record[i]));
    rows.push({ index: cells.index, outcome: outcomeOf(cells.status, cells.collision), cells });
  }
  // `batch --fail-if` adds a verdict column before the parameters; the reason comes after them (results written before it have none).
  const fixed = RESULT_COLUMNS.length + (header[RESULT_COLUMNS.length] === VERDICT_COLUMN ? 1 : 0);
  const end = header.length > fixed && header[header.length - 1] === REASON_COLUMN ? header.length - 1 : header.length;
  return { columns: header, parameters: header.slice(fixed, end), rows };
}

export type SortDirection = 'ascending' | 'descending';
export interface SortOrder {
  column: string;
  direction: SortDirection;
}

function numeric(text: string | undefined): number | undefined {
  if (text === undefined || text.trim() === '') return undefined;
  const value = Number(text);
  return Number.isFinite(value) ? value : undefined;
}

/** Compares two cells: numbers as numbers, before any text; text naturally; empty cells last either way. */
function compareCells(a: string | undefined, b: string | undefined): number {
  const emptyA = a === undefined || a === '';
  const emptyB = b === undefined || b === '';
  if (emptyA || emptyB) return emptyA === emptyB ? 0 : emptyA ? 1 : -1;
  const numberA = numeric(a);
  const numberB = numeric(b);
  if (numberA !== undefined && numberB !== undefined) return numberA - numberB;
  if (numberA !== undefined) return -1;
  if (numberB !== undefined) return 1;
  return a!.localeCompare(b!, undefined, { numeric: true });
}

/** The rows sorted by a column (stable; ties by index); empty cells stay last in both directions. */
export function sortRows(rows: readonly ResultRow[], order: SortOrder): ResultRow[] {
  const sign = order.direction === 'ascending' ? 1 : -1;
  return rows
    .map((row, position) => ({ row, position }))
    .sort((a, b) => {
      const cellA = a.row.cells[order.column];
      const cellB = b.row.cells[order.column];
      const empties = (cellA === '' || cellA === undefined ? 1 : 0) - (cellB === '' || cellB === undefined ? 1 : 0);
      if (empties !== 0) return empties;
      return sign * compareCells(cellA, cellB) || compareCells(a.row.index, b.row.index) || a.position - b.position;
    })
    .map((each) => each.row);
}

/** The rows whose outcome is one of `shown`. */
export function filterRows(rows: readonly ResultRow[], shown: ReadonlySet<Outcome>): ResultRow[] {
  return rows.filter((row) => shown.has(row.outcome));
}

/** How many rows have each outcome. */
export function outcomeCounts(rows: readonly { outcome: Outcome }[]): Record<Outcome, number> {
  const counts: Record<Outcome, number> = { ok: 0, limit: 0, collision: 0, timeout: 0, error: 0, discarded: 0 };
  for (const row of rows) counts[row.outcome]++;
  return counts;
}

/** One axis of the scatter: numbers on a linear scale, anything else as evenly spaced categories. */
export interface ScatterAxis {
  column: string;
  kind: 'number' | 'category';
  /** Where each tick goes (0..1 along the axis) and its label. */
  ticks: { at: number; label: string }[];
  /** A cell's place along the axis (0..1), undefined when it has none (an empty cell). */
  place(cell: string | undefined): number | undefined;
}

export interface ScatterPoint {
  index: string;
  outcome: Outcome;
  /** 0..1 along each axis. */
  x: number;
  y: number;
  label: string;
}

export interface ScatterModel {
  x: ScatterAxis;
  y: ScatterAxis;
  points: ScatterPoint[];
  /** Rows left out because a cell is empty. */
  omitted: number;
}

function niceStep(span: number, count: number): number {
  const raw = span / Math.max(1, count);
  const magnitude = 10 ** Math.floor(Math.log10(raw));
  const scaled = raw / magnitude;
  return (scaled <= 1 ? 1 : scaled <= 2 ? 2 : scaled <= 5 ? 5 : 10) * magnitude;
}

function formatTick(value: number, step: number): string {
  const digits = Math.max(0, Math.min(6, -Math.floor(Math.log10(step) + 1e-9)));
  return value.toFixed(digits);
}

export function scatterAxis(column: string, rows: readonly ResultRow[]): ScatterAxis {
  const cells = rows.map((row) => row.cells[column]).filter((cell): cell is string => cell !== undefined && cell !== '');
  if (cells.length > 0 && cells.every((cell) => numeric(cell) !== undefined)) {
    // A loop, not Math.min(...values): a batch may have a million rows, more than a call takes arguments.
    let low = Infinity;
    let high = -Infinity;
    for (const cell of cells) {
      const value = Number(cell);
      if (value < low) low = value;
      if (value > high) high = value;
    }
    if (low === high) {
      low -= low === 0 ? 1 : Math.abs(low) * 0.1;
      high += high === 0 ? 1 : Math.abs(high) * 0.1;
    }
    const step = niceStep(high - low, 5);
    const ticks: ScatterAxis['ticks'] = [];
    for (let value = Math.ceil(low / step) * step; value <= high + step * 1e-9; value += step) {
      ticks.push({ at: (value - low) / (high - low), label: formatTick(value, step) });
    }
    return {
      column,
      kind: 'number',
      ticks,
      place: (cell) => (numeric(cell) === undefined ? undefined : (Number(cell) - low) / (high - low)),
    };
  }
  const categories = [...new Set(cells)].sort((a, b) => compareCells(a, b));
  const at = (position: number) => (categories.length === 1 ? 0.5 : position / (categories.length - 1));
  const positions = new Map(categories.map((category, position) => [category, at(position)]));
  return {
    column,
    kind: 'category',
    ticks: categories.map((label, position) => ({ at: at(position), label })),
    place: (cell) => (cell === undefined ? undefined : positions.get(cell)),
  };
}

/** The scatter of two columns: every row with both cells, at its place along each axis. */
export function scatterModel(rows: readonly ResultRow[], xColumn: string, yColumn: string): ScatterModel {
  const x = scatterAxis(xColumn, rows);
  const y = scatterAxis(yColumn, rows);
  const points: ScatterPoint[] = [];
  let omitted = 0;
  for (const row of rows) {
    const px = x.place(row.cells[xColumn]);
    const py = y.place(row.cells[yColumn]);
    if (px === undefined || py === undefined) {
      omitted++;
      continue;
    }
    points.push({
      index: row.index,
      outcome: row.outcome,
      x: px,
      y: py,
      label: `#${row.index} ${row.outcome}: ${xColumn}=${row.cells[xColumn]}, ${yColumn}=${row.cells[yColumn]}`,
    });
  }
  return { x, y, points, omitted };
}

/**
 * The two columns a scatter shows first: the first two parameters, else the measures, else the index; a column
 * no row has a value in (min_ttc_s when no gap ever closes) is never one of them, so the first view is never empty.
 */
export function defaultAxes(table: ResultsTable): { x: string; y: string } {
  const filled = (column: string) => table.rows.some((row) => (row.cells[column] ?? '') !== '');
  const candidates = [...table.parameters, 'min_distance_m', 'min_ttc_s', 'end_time_s', 'index'].filter(
    (column, position, all) => all.indexOf(column) === position && (column === 'index' || filled(column)),
  );
  const [x, y] = candidates;
  return { x, y: y ?? 'index' };
}

/** Characters a tick label shows at most; the whole label is its `<title>`. */
const TICK_LABEL_CHARS = 18;
/** Width of a character of the 11 px sans-serif labels, generously, to keep labels apart. */
const CHAR_WIDTH = 6.5;

function tickLabel(label: string): string {
  return label.length <= TICK_LABEL_CHARS ? label : `…${label.slice(label.length - TICK_LABEL_CHARS + 1)}`;
}

export function escapeHtml(text: string): string {
  return text.replace(/[&<>"']/g, (char) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[char]!);
}

export interface ScatterStyle {
  width: number;
  height: number;
  /** Text and axis colour. */
  foreground: string;
  /** Grid lines. */
  grid: string;
  fontFamily: string;
}

/** The scatter as an SVG element; each point is a circle with `data-index` and a `<title>`, plus a legend. */
export function scatterSvg(model: ScatterModel, style: ScatterStyle): string {
  const margin = { left: 64, right: 120, top: 16, bottom: 48 };
  const plotWidth = Math.max(40, style.width - margin.left - margin.right);
  const plotHeight = Math.max(40, style.height - margin.top - margin.bottom);
  // Points keep off the frame: 4 % inset on each side.
  const sx = (at: number) => margin.left + plotWidth * (0.04 + 0.92 * at);
  const sy = (at: number) => margin.top + plotHeight * (0.96 - 0.92 * at);
  const round = (value: number) => Math.round(value * 10) / 10;
  const parts: string[] = [];
  parts.push(
    `<svg xmlns="http://www.w3.org/2000/svg" class="scatter" width="${style.width}" height="${style.height}" viewBox="0 0 ${style.width} ${style.height}" font-family="${escapeHtml(style.fontFamily)}" font-size="11" role="img" aria-label="${escapeHtml(`${model.y.column} against ${model.x.column}`)}">`,
  );
  parts.push(
    `<rect x="${margin.left}" y="${margin.top}" width="${plotWidth}" height="${plotHeight}" fill="none" stroke="${style.foreground}" stroke-opacity="0.5"/>`,
  );
  // A label that would overlap the last one drawn is left out (its grid line stays): long category names do not run together.
  let lastRight = -Infinity;
  for (const tick of model.x.ticks) {
    const x = round(sx(tick.at));
    parts.push(`<line x1="${x}" y1="${margin.top}" x2="${x}" y2="${margin.top + plotHeight}" stroke="${style.grid}"/>`);
    const shown = tickLabel(tick.label);
    const half = (shown.length * CHAR_WIDTH) / 2;
    if (x - half < lastRight + 4) continue;
    lastRight = x + half;
    parts.push(
      `<text x="${x}" y="${margin.top + plotHeight + 14}" text-anchor="middle" fill="${style.foreground}"><title>${escapeHtml(tick.label)}</title>${escapeHtml(shown)}</text>`,
    );
  }
  let lastTop = Infinity;
  for (const tick of model.y.ticks) {
    const y = round(sy(tick.at));
    parts.push(`<line x1="${margin.left}" y1="${y}" x2="${margin.left + plotWidth}" y2="${y}" stroke="${style.grid}"/>`);
    if (y + 6 > lastTop) continue;
    lastTop = y - 6;
    const shown = tick.label;
    parts.push(
      `<text x="${margin.left - 6}" y="${y + 4}" text-anchor="end" fill="${style.foreground}"><title>${escapeHtml(tick.label)}</title>${escapeHtml(shown)}</text>`,
    );
  }
  parts.push(
    `<text class="axis-x" x="${margin.left + plotWidth / 2}" y="${style.height - 10}" text-anchor="middle" font-weight="bold" fill="${style.foreground}">${escapeHtml(model.x.column)}</text>`,
  );
  parts.push(
    `<text class="axis-y" transform="translate(14 ${margin.top + plotHeight / 2}) rotate(-90)" text-anchor="middle" font-weight="bold" fill="${style.foreground}">${escapeHtml(model.y.column)}</text>`,
  );
  // Runs with the same two values (they differ in another parameter) are set around their place, so each shows and can be clicked.
  const offsets = new Map<ScatterPoint, { dx: number; dy: number }>();
  const byPlace = new Map<string, ScatterPoint[]>();
  for (const point of model.points) {
    const place = `${point.x},${point.y}`;
    const group = byPlace.get(place);
    if (group) group.push(point);
    else byPlace.set(place, [point]);
  }
  for (const group of byPlace.values()) {
    group.forEach((point, k) => {
      const angle = (2 * Math.PI * k) / group.length - Math.PI / 2;
      const radius = group.length === 1 ? 0 : Math.min(14, 4 + group.length);
      offsets.set(point, { dx: radius * Math.cos(angle), dy: radius * Math.sin(angle) });
    });
  }
  // Collisions and errors are drawn last, so that what failed is on top.
  const drawOrder: Outcome[] = ['discarded', 'ok', 'limit', 'timeout', 'error', 'collision'];
  for (const outcome of drawOrder) {
    for (const point of model.points) {
      if (point.outcome !== outcome) continue;
      const { dx, dy } = offsets.get(point)!;
      parts.push(
        `<circle class="point" data-index="${escapeHtml(point.index)}" cx="${round(sx(point.x) + dx)}" cy="${round(sy(point.y) + dy)}" r="4.5" fill="${OUTCOME_COLORS[outcome]}" fill-opacity="0.85" stroke="${style.foreground}" stroke-opacity="0.4"><title>${escapeHtml(point.label)}</title></circle>`,
      );
    }
  }
  const legendX = margin.left + plotWidth + 16;
  const counts = outcomeCounts(model.points);
  OUTCOMES.forEach((outcome, i) => {
    const y = margin.top + 10 + i * 18;
    const count = counts[outcome];
    parts.push(
      `<circle cx="${legendX + 5}" cy="${y}" r="5" fill="${OUTCOME_COLORS[outcome]}"/><text class="legend" x="${legendX + 16}" y="${y + 4}" fill="${style.foreground}">${outcome} (${count})</text>`,
    );
  });
  const notes: string[] = [];
  if ([...byPlace.values()].some((group) => group.length > 1)) notes.push('same values: set', 'around their place');
  if (model.omitted > 0) notes.push(`${model.omitted} without values`);
  notes.forEach((note, i) =>
    parts.push(
      `<text x="${legendX}" y="${margin.top + 14 + (OUTCOMES.length + i) * 18}" fill="${style.foreground}" fill-opacity="0.7">${escapeHtml(note)}</text>`,
    ),
  );
  parts.push('</svg>');
  return parts.join('');
}

/**
 * The table as HTML: a header cell per column (with `data-column`, and the sort shown), a row per result with
 * `data-index`; `interactive` (the view) makes each header a sort button and each index a link that opens its run.
 */
export function tableHtml(
  columns: readonly string[],
  rows: readonly ResultRow[],
  order?: SortOrder,
  interactive = false,
  /** The index of the run last opened, marked (class `selected`, `aria-selected`) so that the page can show it. */
  selected?: string,
): string {
  const head = columns
    .map((column) => {
      const sorted = order?.column === column ? order.direction : undefined;
      const arrow = sorted === 'ascending' ? ' ▲' : sorted === 'descending' ? ' ▼' : '';
      const label = `${escapeHtml(column)}${arrow}`;
      const content = interactive ? `<button class="sort" title="Sort by ${escapeHtml(column)}">${label}</button>` : label;
      return `<th data-column="${escapeHtml(column)}"${column === REASON_COLUMN ? ' class="reason"' : ''}${sorted ? ` aria-sort="${sorted}"` : ''}>${content}</th>`;
    })
    .join('');
  const body = rows
    .map((row) => {
      const cells = columns.map((column) => {
        const text = escapeHtml(row.cells[column] ?? '');
        // The reason is a sentence: read from its start and wrapped within the view (class reason), where the numbers align right.
        return `<td${column === REASON_COLUMN ? ' class="reason"' : ''}>${interactive && column === 'index' ? `<a href="#" class="open" title="Open run ${text} in the bird's-eye view">#${text}</a>` : text}</td>`;
      });
      const mark = selected !== undefined && row.index === selected ? ' selected" aria-selected="true' : '';
      return `<tr class="${row.outcome}${mark}" data-index="${escapeHtml(row.index)}">${cells.join('')}</tr>`;
    })
    .join('\n');
  return `<table class="results"><thead><tr>${head}</tr></thead><tbody>\n${body}\n</tbody></table>`;
}

/** One line: how many runs, and how many of each outcome. */
export function summaryText(rows: readonly ResultRow[]): string {
  const counts = outcomeCounts(rows);
  const judged = rows.filter((row) => row.cells[VERDICT_COLUMN]);
  const failed = judged.filter((row) => row.cells[VERDICT_COLUMN] === 'fail').length;
  const verdicts = judged.length > 0 ? `; against the criteria ${judged.length - failed} pass, ${failed} fail` : '';
  // A collision outranks the status the row shows ('ok', 'limit'): say so, or '0 ok' beside rows that say ok reads as a contradiction.
  const counted = (outcome: Outcome) =>
    outcome === 'collision' && counts.collision > 0
      ? `${counts.collision} collision (esmini logged one; the status column says how each run ended)`
      : `${counts[outcome]} ${outcome}`;
  return `${rows.length} run${rows.length === 1 ? '' : 's'}: ${OUTCOMES.map(counted).join(', ')}${verdicts}`;
}

/**
 * results.html: the table (by index) and the scatter of the default axes, with everything inline (no script,
 * no network), readable in any browser and printable; well-formed XML too (after its DOCTYPE), so tools can read it.
 */
export function resultsReportHtml(table: ResultsTable, title: string): string {
  const axes = defaultAxes(table);
  const rows = sortRows(table.rows, { column: 'index', direction: 'ascending' });
  const scatter = scatterSvg(scatterModel(rows, axes.x, axes.y), {
    width: 760,
    height: 420,
    foreground: '#222222',
    grid: '#dddddd',
    fontFamily: 'sans-serif',
  });
  const rowStyles = OUTCOMES.map((outcome) => `tr.${outcome} td:nth-child(2){border-left:4px solid ${OUTCOME_COLORS[outcome]}}`).join('\n');
  return `<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"/>
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; style-src 'unsafe-inline'; img-src data:"/>
<title>${escapeHtml(title)}</title>
<style>
body{font-family:sans-serif;font-size:13px;color:#222;margin:16px}
h1{font-size:18px} table.results{border-collapse:collapse} th,td{border:1px solid #ccc;padding:2px 8px;text-align:right} th{background:#f0f0f0;position:sticky;top:0}
th.reason,td.reason{text-align:left}
${rowStyles}
</style></head><body>
<h1>${escapeHtml(title)}</h1>
<p class="summary">${escapeHtml(summaryText(rows))}</p>
<figure>${scatter}<figcaption>${escapeHtml(axes.y)} against ${escapeHtml(axes.x)}, coloured by outcome</figcaption></figure>
${tableHtml(table.columns, rows)}
</body></html>
`;
}
