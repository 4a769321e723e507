import * as fs from 'node:fs';
import * as path from 'node:path';
import { writeFileAtomic } from '../../../common/src/atomic';
import { parseResultsCsv, REASON_COLUMN, ResultRow, resultsReportHtml, VERDICT_COLUMN } from '../../../common/src/variationsReport';
import { Criterion, judge } from './criteria';
import { junitXml } from './junit';
import { BatchRow } from './row';
export { BatchRow, RUN_STATUSES, RunStatus } from './row';

/** results.json is written again at most this often while a batch runs (it reads every row back), and at its end. */
const JSON_INTERVAL_MS = 30_000;

export const FIXED_COLUMNS = ['index', 'status', 'collision', 'min_distance_m', 'min_ttc_s', 'end_time_s'] as const;
export { REASON_COLUMN, VERDICT_COLUMN } from '../../../common/src/variationsReport';

/** What identifies a batch: resuming into a folder written by another one is refused rather than mixed. */
export interface BatchIdentity {
  distribution: string;
  scenarioSha256: string;
  distributionSha256: string;
  sample: string | null;
  seed: number;
  /** The limit the user set, in simulated seconds; null: each scenario's own end. */
  duration: number | null;
  esminiSeed: number;
  /** The --fail-if criteria, joined by '; '; absent without any (so results written before them still resume). */
  criteria?: string;
}

export class ResultsError extends Error {}

/** A CSV field as RFC 4180 quotes it when it must. */
export function csvField(value: string): string {
  return /[",\r\n]/.test(value) || value !== value.trim() ? `"${value.replace(/"/g, '""')}"` : value;
}

function number(value: number | null, digits: number): string {
  return value === null ? '' : value.toFixed(digits);
}

export function csvLine(row: BatchRow, parameterNames: string[], withVerdict = false): string {
  const fixed = [
    row.index,
    row.status,
    String(row.collision),
    number(row.min_distance_m, 3),
    number(row.min_ttc_s, 3),
    number(row.end_time_s, 3),
    ...(withVerdict ? [row.verdict ?? ''] : []),
  ];
  return [...fixed, ...parameterNames.map((name) => row.parameters[name] ?? ''), reasonOf(row)].map(csvField).join(',') + '\n';
}

/** A row's reason; a worker older than the field sends none, and its message says why then. */
function reasonOf(row: BatchRow): string {
  return (row.reason ?? (row.status === 'ok' ? '' : (row.message ?? ''))).replace(/\s+/g, ' ');
}

/** The first field of each complete line after the header: the indices already in results.csv. */
function indicesIn(csv: string): string[] {
  const lines = csv.split('\n');
  lines.pop();
  return lines.slice(1).map((line) => (line.startsWith('"') ? line.slice(1, line.indexOf('"', 1)) : line.slice(0, line.indexOf(','))));
}

/** The records of a CSV text, each with its line end: a quoted field may hold a line break. */
function csvRecords(csv: string): string[] {
  const records: string[] = [];
  let start = 0;
  let quoted = false;
  for (let at = 0; at < csv.length; at++) {
    if (csv[at] === '"') quoted = !quoted;
    else if (csv[at] === '\n' && !quoted) {
      records.push(csv.slice(start, at + 1));
      start = at + 1;
    }
  }
  if (start < csv.length) records.push(csv.slice(start));
  return records;
}

/** The index a record of results.csv begins with (its first field, unquoted). */
function recordIndex(record: string): bigint {
  const field = record.startsWith('"') ? record.slice(1, record.indexOf('"', 1)) : record.slice(0, record.indexOf(','));
  return /^\d+$/.test(field) ? BigInt(field) : -1n;
}

/** results.csv's text with its rows in index order (the header first, each row as it was written). */
export function csvInIndexOrder(csv: string): string {
  const [header = '', ...rows] = csvRecords(csv);
  const sorted = rows
    .map((record) => ({ record, index: recordIndex(record) }))
    .sort((a, b) => (a.index < b.index ? -1 : a.index > b.index ? 1 : 0));
  return header + sorted.map((row) => row.record).join('');
}

/**
 * DIR/results.csv, DIR/results.json and what lets a batch resume. Every row is appended and synced to disk as
 * its run ends, first to DIR/.rows.jsonl (the rows with esmini's messages), then to results.csv, which says
 * what is done: a row cut short by a kill is dropped on the next start, so the CSV is always whole rows.
 * results.json is written from the rows, atomically, now and then and at the end; at the end (an interrupted
 * batch's too) results.csv is written again, atomically, with its rows in index order as results.json has them.
 */
export class ResultsFolder {
  readonly csvFile: string;
  readonly jsonFile: string;
  /** The self-contained report (table and scatter) written beside results.csv at the end. */
  readonly htmlFile: string;
  private readonly rowsFile: string;
  private readonly identityFile: string;
  private csv: fs.promises.FileHandle | undefined;
  private rows: fs.promises.FileHandle | undefined;
  private queue: Promise<void> = Promise.resolve();
  private lastJson = 0;

  private constructor(
    readonly folder: string,
    readonly parameterNames: string[],
    /** Indices whose rows are in results.csv. */
    readonly done: Set<string>,
    private readonly identity: BatchIdentity,
    /** --fail-if: each row gets a verdict column. */
    readonly criteria: Criterion[],
    /** Where the JUnit XML goes at the end (--junit). */
    readonly junitFile: string | undefined,
  ) {
    this.csvFile = path.join(folder, 'results.csv');
    this.jsonFile = path.join(folder, 'results.json');
    this.htmlFile = path.join(folder, 'results.html');
    this.rowsFile = path.join(folder, '.rows.jsonl');
    this.identityFile = path.join(folder, '.batch.json');
  }

  /** The header line of results.csv. */
  static header(parameterNames: string[], withVerdict = false): string {
    return ResultsFolder.columns(parameterNames, withVerdict).map(csvField).join(',') + '\n';
  }

  static columns(parameterNames: string[], withVerdict: boolean): string[] {
    return [...FIXED_COLUMNS, ...(withVerdict ? [VERDICT_COLUMN] : []), ...parameterNames, REASON_COLUMN];
  }

  /** The rows whose verdict is fail: those appended, and on a resume those already in results.csv. */
  readonly failedRows: BatchRow[] = [];

  /** Set by `finish` from the whole of results.csv (resumed rows too): what says that runs did not happen, and why. */
  notDone: string | undefined;

  /**
   * Opens (creating) the results folder. A folder holding another batch's results (other columns, another
   * distribution or sampling) is refused with ResultsError; nothing in it is changed then.
   */
  static async open(
    folder: string,
    parameterNames: string[],
    identity: BatchIdentity,
    criteria: Criterion[] = [],
    junitFile?: string,
  ): Promise<ResultsFolder> {
    const results = new ResultsFolder(folder, parameterNames, new Set(), identity, criteria, junitFile);
    const header = ResultsFolder.header(parameterNames, criteria.length > 0);
    let existing: string | undefined;
    try {
      existing = await fs.promises.readFile(results.csvFile, 'utf8');
    } catch (error) {
      if ((error as NodeJS.ErrnoException).code !== 'ENOENT')
        throw new ResultsError(`cannot read ${results.csvFile}: ${(error as Error).message}`);
    }
    if (existing !== undefined && existing.length > 0) {
      if (!existing.startsWith(header))
        throw new ResultsError(
          `${results.csvFile} holds another batch's results (its columns are not ${header.trim()}); use another --results folder`,
        );
      let stored: BatchIdentity | undefined;
      try {
        stored = JSON.parse(await fs.promises.readFile(results.identityFile, 'utf8')) as BatchIdentity;
      } catch {
        stored = undefined;
      }
      const differs = stored ? (Object.keys(identity) as (keyof BatchIdentity)[]).filter((key) => stored[key] !== identity[key]) : [];
      if (differs.length > 0)
        throw new ResultsError(
          `${results.csvFile} holds another batch's results (it differs in ${differs.join(', ')}); use another --results folder`,
        );
      const whole = existing.slice(0, existing.lastIndexOf('\n') + 1);
      for (const index of indicesIn(whole)) results.done.add(index);
      if (criteria.length > 0) results.failedRows.push(...(await results.readRows()).filter((row) => row.verdict === 'fail'));
      if (whole.length < existing.length) await fs.promises.truncate(results.csvFile, Buffer.byteLength(whole));
    }
    try {
      await fs.promises.mkdir(folder, { recursive: true });
      await writeFileAtomic(results.identityFile, JSON.stringify(identity, null, 2) + '\n');
      if (existing === undefined || existing.length === 0) {
        await fs.promises.writeFile(results.rowsFile, '');
        await writeFileAtomic(results.csvFile, header);
      }
      results.rows = await fs.promises.open(results.rowsFile, 'a');
      results.csv = await fs.promises.open(results.csvFile, 'a');
    } catch (error) {
      await results.close();
      throw new ResultsError(`cannot write in ${folder}: ${(error as Error).message}`);
    }
    return results;
  }

  /** Appends a row and syncs it to disk; rows are written one at a time in the order they come. */
  append(result: BatchRow): Promise<void> {
    const write = async () => {
      if (this.done.has(result.index)) return;
      const judged = this.criteria.length > 0 ? judge(result, this.criteria) : undefined;
      const row = judged ? { ...result, verdict: judged.verdict, failed: judged.reasons } : result;
      await this.rows!.appendFile(JSON.stringify(row) + '\n');
      await this.rows!.datasync();
      await this.csv!.appendFile(csvLine(row, this.parameterNames, this.criteria.length > 0));
      await this.csv!.datasync();
      this.done.add(row.index);
      if (row.verdict === 'fail') this.failedRows.push(row);
      if (Date.now() - this.lastJson > JSON_INTERVAL_MS) await this.writeJson();
    };
    this.queue = this.queue.then(write);
    return this.queue;
  }

  /** results.json from every row in results.csv, in index order, written atomically. */
  async writeJson(): Promise<BatchRow[]> {
    this.lastJson = Date.now();
    const rows = await this.readRows();
    const document = { ...this.identity, columns: ResultsFolder.columns(this.parameterNames, this.criteria.length > 0), rows };
    await writeFileAtomic(this.jsonFile, JSON.stringify(document, null, 1) + '\n');
    return rows;
  }

  /** The rows of every index in results.csv, from .rows.jsonl, in index order. */
  private async readRows(): Promise<BatchRow[]> {
    const text = await fs.promises.readFile(this.rowsFile, 'utf8').catch(() => '');
    const byIndex = new Map<string, BatchRow>();
    for (const line of text.split('\n')) {
      if (!line.trim()) continue;
      try {
        const row = JSON.parse(line) as BatchRow;
        if (this.done.has(row.index)) byIndex.set(row.index, row);
      } catch {
        // A line cut short by a kill: its run is not in results.csv either and runs again.
      }
    }
    return [...byIndex.values()].sort((a, b) => (BigInt(a.index) < BigInt(b.index) ? -1 : 1));
  }

  /** results.html from results.csv as it is, written atomically. */
  async writeReport(): Promise<void> {
    const csv = await fs.promises.readFile(this.csvFile, 'utf8');
    const title = `Variations of ${path.basename(this.identity.distribution)}`;
    const table = parseResultsCsv(csv);
    this.notDone = notDoneSummary(table.rows, this.csvFile);
    await writeFileAtomic(this.htmlFile, resultsReportHtml(table, title));
  }

  /** Waits for the rows in flight, puts results.csv in index order, writes results.json and results.html and closes the files. */
  async finish(): Promise<void> {
    await this.queue;
    await this.csv?.close();
    this.csv = undefined;
    // Rows were appended as runs ended, in any order: the finished file lists them by index (rows are kept as written).
    const csv = await fs.promises.readFile(this.csvFile, 'utf8');
    const ordered = csvInIndexOrder(csv);
    if (ordered !== csv) await writeFileAtomic(this.csvFile, ordered);
    const rows = await this.writeJson();
    await this.writeReport();
    if (this.junitFile)
      await writeFileAtomic(
        this.junitFile,
        junitXml(rows, this.parameterNames, path.basename(this.identity.distribution), this.identity.criteria),
      );
    await this.close();
  }

  async close(): Promise<void> {
    await this.csv?.close();
    await this.rows?.close();
    this.csv = undefined;
    this.rows = undefined;
  }
}

/** Distinct reasons a batch's end names at most, each with the first few indices. */
const REASONS_SHOWN = 5;
const INDICES_SHOWN = 5;

/**
 * What a batch says at its end when runs did not happen (status error: esmini refused the scenario, could not be
 * started, or reported an error): how many, and each distinct reason with the runs it holds for; undefined when none.
 */
export function notDoneSummary(rows: readonly ResultRow[], csvFile: string): string | undefined {
  const byReason = new Map<string, string[]>();
  let ran = 0;
  for (const row of rows) {
    if (row.cells.status !== 'discarded') ran++;
    if (row.cells.status !== 'error') continue;
    const reason = row.cells[REASON_COLUMN] || 'esmini reported an error (no reason recorded)';
    const indices = byReason.get(reason);
    if (indices) indices.push(row.index);
    else byReason.set(reason, [row.index]);
  }
  if (byReason.size === 0) return undefined;
  const count = [...byReason.values()].reduce((sum, indices) => sum + indices.length, 0);
  const groups = [...byReason].sort((a, b) => b[1].length - a[1].length);
  const lines = groups.slice(0, REASONS_SHOWN).map(([reason, indices]) => {
    indices.sort((a, b) => (BigInt(a) < BigInt(b) ? -1 : BigInt(a) > BigInt(b) ? 1 : 0));
    const shown = indices.slice(0, INDICES_SHOWN).map((index) => `#${index}`);
    const more = indices.length > shown.length ? ` and ${indices.length - shown.length} more` : '';
    return `\n  ${shown.join(', ')}${more}: ${reason}`;
  });
  const moreReasons = groups.length > REASONS_SHOWN ? `\n  (${groups.length - REASONS_SHOWN} other reasons)` : '';
  return (
    `${count} of ${ran} run${ran === 1 ? '' : 's'} failed in esmini (status error); the column ${REASON_COLUMN} of ${csvFile} ` +
    `says why for each:${lines.join('')}${moreReasons}`
  );
}

/** What a batch says at its end when runs fail its criteria: how many, and the first few with why. */
export function criteriaFailure(results: ResultsFolder): string | undefined {
  const failed = results.failedRows;
  if (failed.length === 0) return undefined;
  const sorted = [...failed].sort((a, b) => (BigInt(a.index) < BigInt(b.index) ? -1 : 1));
  const shown = sorted.slice(0, 5).map((row) => `#${row.index}: ${(row.failed ?? []).join('; ')}`);
  const more = failed.length > shown.length ? `; ${failed.length - shown.length} more in ${results.csvFile}` : '';
  return `${failed.length} run${failed.length === 1 ? '' : 's'} failed the criteria (${results.criteria.map((each) => each.text).join('; ')}): ${shown.join('; ')}${more}`;
}
