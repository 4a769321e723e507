/**
 * The Variations view's page: a batch's results as a table (sorted by a header click, filtered by outcome) and a
 * scatter of two columns coloured by outcome; a click on a row or a point asks the extension to open that run.
 * The table and the scatter are drawn by common/src/variationsReport.ts, as results.html is.
 */
import {
  defaultAxes,
  escapeHtml,
  filterRows,
  Outcome,
  OUTCOME_COLORS,
  outcomeCounts,
  OUTCOMES,
  ResultsTable,
  scatterModel,
  scatterSvg,
  SortOrder,
  sortRows,
  summaryText,
  tableHtml,
} from '../../../../common/src/variationsReport';
import type { FromView, ToView } from '../messages';

declare function acquireVsCodeApi(): { postMessage(message: FromView): void };
const vscode = acquireVsCodeApi();

/** The table shows at most this many rows at once (sorting and filtering choose which); the scatter shows all. */
const MAX_TABLE_ROWS = 2000;
/** Columns besides the parameters that make sense on an axis. */
const MEASURED_COLUMNS = ['min_distance_m', 'min_ttc_s', 'end_time_s', 'index'];

const element = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
const titleElement = element<HTMLSpanElement>('title');
const filtersElement = element<HTMLSpanElement>('filters');
const xSelect = element<HTMLSelectElement>('xAxis');
const ySelect = element<HTMLSelectElement>('yAxis');
const summaryElement = element<HTMLDivElement>('summary');
const plotElement = element<HTMLDivElement>('plot');
const tableElement = element<HTMLDivElement>('table');
const noteElement = element<HTMLDivElement>('note');
const noticeElement = element<HTMLDivElement>('notice');

let table: ResultsTable | undefined;
let runsKept = false;
let order: SortOrder = { column: 'index', direction: 'ascending' };
const shown = new Set<Outcome>(OUTCOMES);
let axes = { x: 'index', y: 'min_distance_m' };
let selected: string | undefined;
/** What the scatter shown was drawn from. */
let drawnPlot: string | undefined;

function themeColor(name: string, fallback: string): string {
  return getComputedStyle(document.body).getPropertyValue(name).trim() || fallback;
}

function axisChoices(current: ResultsTable): string[] {
  return [...current.parameters, ...MEASURED_COLUMNS];
}

function fillSelect(select: HTMLSelectElement, choices: string[], value: string): void {
  select.innerHTML = choices
    .map((choice) => `<option value="${escapeHtml(choice)}"${choice === value ? ' selected' : ''}>${escapeHtml(choice)}</option>`)
    .join('');
}

function renderFilters(current: ResultsTable): void {
  const counts = outcomeCounts(current.rows);
  filtersElement.innerHTML = OUTCOMES.map(
    (outcome) =>
      `<button class="outcome" data-outcome="${outcome}" aria-pressed="${shown.has(outcome)}" title="Show or hide the runs whose outcome is ${outcome}"><span class="swatch" style="background:${OUTCOME_COLORS[outcome]}"></span>${outcome} (${counts[outcome]})</button>`,
  ).join(' ');
}

function render(): void {
  if (!table) return;
  const filtered = filterRows(table.rows, shown);
  const sorted = sortRows(filtered, order);
  const model = scatterModel(filtered, axes.x, axes.y);
  const width = Math.max(320, plotElement.clientWidth - 16);
  const height = Math.max(220, Math.min(420, Math.round(window.innerHeight * 0.42)));
  // Sorting changes only the table: the scatter of a large batch is drawn again only when what it shows changes.
  const plotKey = JSON.stringify([table.rows.length, [...shown], axes, width, height]);
  if (plotKey !== drawnPlot) {
    const foreground = themeColor('--vscode-foreground', '#cccccc');
    plotElement.innerHTML = scatterSvg(model, {
      width,
      height,
      foreground,
      grid: themeColor('--vscode-panel-border', '#80808040'),
      fontFamily: themeColor('--vscode-font-family', 'sans-serif'),
    });
    drawnPlot = plotKey;
  }
  const visible = sorted.slice(0, MAX_TABLE_ROWS);
  tableElement.innerHTML = tableHtml(table.columns, visible, order, runsKept, selected);
  summaryElement.textContent = `${summaryText(table.rows)}; ${filtered.length} shown${runsKept ? '; click a row or a point to open its run' : '; the runs were not kept (batch --keep-runs), so they cannot be opened'}`;
  noteElement.textContent =
    sorted.length > visible.length ? `The first ${visible.length} of ${sorted.length} rows: sort or filter to see others.` : '';
  markSelected();
  vscode.postMessage({
    type: 'rendered',
    stats: {
      rows: table.rows.length,
      shown: filtered.length,
      points: model.points.length,
      sort: order,
      x: axes.x,
      y: axes.y,
      outcomes: [...shown],
    },
  });
}

function markSelected(): void {
  document.querySelectorAll('.selected').forEach((each) => {
    each.classList.remove('selected');
    each.removeAttribute('aria-selected');
  });
  if (selected === undefined) return;
  document.querySelectorAll(`[data-index="${CSS.escape(selected)}"]`).forEach((each) => {
    each.classList.add('selected');
    if (each.tagName === 'TR') each.setAttribute('aria-selected', 'true');
  });
}

function open(index: string): void {
  selected = index;
  noticeElement.textContent = '';
  markSelected();
  vscode.postMessage({ type: 'openRun', index });
}

tableElement.addEventListener('click', (event) => {
  const target = event.target as HTMLElement;
  const header = target.closest('th');
  if (header?.dataset.column) {
    const column = header.dataset.column;
    order = { column, direction: order.column === column && order.direction === 'ascending' ? 'descending' : 'ascending' };
    render();
    return;
  }
  const row = target.closest('tr');
  if (row?.dataset.index !== undefined) {
    event.preventDefault();
    open(row.dataset.index);
  }
});

plotElement.addEventListener('click', (event) => {
  const point = (event.target as Element).closest('circle.point');
  const index = point?.getAttribute('data-index');
  if (index !== null && index !== undefined) open(index);
});

filtersElement.addEventListener('click', (event) => {
  const button = (event.target as HTMLElement).closest('button');
  const outcome = button?.dataset.outcome as Outcome | undefined;
  if (!button || !outcome) return;
  if (shown.has(outcome)) shown.delete(outcome);
  else shown.add(outcome);
  button.setAttribute('aria-pressed', String(shown.has(outcome)));
  render();
});

for (const [select, axis] of [
  [xSelect, 'x'],
  [ySelect, 'y'],
] as const) {
  select.addEventListener('change', () => {
    axes = { ...axes, [axis]: select.value };
    render();
  });
}

let resizeTimer: number | undefined;
window.addEventListener('resize', () => {
  clearTimeout(resizeTimer);
  resizeTimer = window.setTimeout(render, 150);
});

window.addEventListener('message', (event: MessageEvent<ToView>) => {
  const message = event.data;
  if (message.type === 'notice') {
    noticeElement.textContent = message.message;
    return;
  }
  if (message.type === 'error') {
    titleElement.textContent = 'Variations';
    summaryElement.innerHTML = `<span class="error">${escapeHtml(message.message)}</span>`;
    plotElement.innerHTML = '';
    tableElement.innerHTML = '';
    return;
  }
  // New results (a new run of the batch): what was said about a click on the previous ones no longer holds.
  noticeElement.textContent = '';
  const first = table === undefined || table.columns.join(',') !== message.table.columns.join(',');
  table = message.table;
  runsKept = message.runs;
  drawnPlot = undefined;
  titleElement.textContent = `Variations of ${message.title}`;
  const choices = axisChoices(table);
  if (first || !choices.includes(axes.x) || !choices.includes(axes.y)) axes = defaultAxes(table);
  if (!table.columns.includes(order.column)) order = { column: 'index', direction: 'ascending' };
  fillSelect(xSelect, choices, axes.x);
  fillSelect(ySelect, choices, axes.y);
  renderFilters(table);
  render();
});

vscode.postMessage({ type: 'ready' });
