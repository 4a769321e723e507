/**
 * esmini's `--csv_logger` output (esmini 3.6.0, CSVLogger.cpp): six header lines, a column line
 * `Index [-], TimeStamp [s], #1 Entity_Name [-], ...` naming each entity's columns with a `#k `
 * prefix, then one row per time step. Also the state changes esmini logs for storyboard elements.
 */

export interface EntityTrack {
  name: string;
  /** Bounding box, from the first row. */
  length: number;
  width: number;
  /** Where the bounding box's center is ahead of the reference point. */
  centerX: number;
  x: Float64Array;
  y: Float64Array;
  hdg: Float64Array;
  speed: Float64Array;
}

export interface EsminiRun {
  /** From the header, e.g. `v3.6.0-1-77028d83`. */
  version: string;
  scenarioFile: string;
  /** Simulation time of each row. */
  times: Float64Array;
  entities: EntityTrack[];
  /** True when rows beyond `maxRows` were left out. */
  truncated: boolean;
}

export class EsminiCsvError extends Error {
  constructor(
    message: string,
    readonly line: number,
  ) {
    super(`line ${line}: ${message}`);
  }
}

const FIELDS = {
  name: 'Entity_Name',
  x: 'World_Position_X',
  y: 'World_Position_Y',
  hdg: 'World_Heading_Angle',
  speed: 'Current_Speed',
  length: 'bb_length',
  width: 'bb_width',
  centerX: 'bb_x',
} as const;
type Field = keyof typeof FIELDS;

/** `#2 World_Position_X [m]` → entity 2, field `World_Position_X`. */
function columnName(header: string): { entity: number; field: string } | undefined {
  const match = /^#(\d+)\s+([A-Za-z_]+)/.exec(header.trim());
  return match ? { entity: Number(match[1]), field: match[2] } : undefined;
}

/**
 * Whether any entity's world position changes between the rows of an esmini CSV log, read line by line (`lines` yields
 * it in order; it may stop early): true at the first change, false when every entity stood still over two rows or more,
 * undefined when there is no column line or fewer than two rows.
 */
export function anyEntityMoved(lines: Iterable<string>): boolean | undefined {
  let positions: number[] | undefined;
  let first: number[] | undefined;
  let rows = 0;
  for (const line of lines) {
    if (!positions) {
      if (!line.startsWith('Index')) continue;
      const headers = line.split(',');
      positions = headers.flatMap((header, index) =>
        /^(World_Position_X|World_Position_Y)$/.test(columnName(header)?.field ?? '') ? [index] : [],
      );
      if (positions.length === 0) return undefined;
      continue;
    }
    const fields = line.split(',');
    if (fields.length <= Math.max(...positions)) continue;
    const values = positions.map((index) => Number(fields[index]));
    if (values.some((value) => !Number.isFinite(value))) continue;
    rows++;
    if (!first) first = values;
    else if (values.some((value, index) => Math.abs(value - (first as number[])[index]) > 1e-6)) return true;
  }
  return rows >= 2 ? false : undefined;
}

/** Reads an esmini CSV log. Throws EsminiCsvError, naming the line, when it is not one. */
export function parseEsminiCsv(text: string, options: { maxRows?: number } = {}): EsminiRun {
  const maxRows = options.maxRows ?? 1_000_000;
  const lines = text.split(/\r?\n/);
  const headerValue = (prefix: string) =>
    lines
      .slice(0, 6)
      .find((line) => line.startsWith(prefix))
      ?.slice(prefix.length)
      .trim() ?? '';
  const columnLine = lines.findIndex((line, index) => index < 20 && line.startsWith('Index'));
  if (!lines[0]?.startsWith('esmini') || columnLine < 0)
    throw new EsminiCsvError('not an esmini CSV log: expected esmini header lines and an `Index [-], TimeStamp [s], ...` column line', 1);
  const headers = lines[columnLine].split(',');
  const columns = new Map<number, Partial<Record<Field, number>>>();
  headers.forEach((header, index) => {
    const column = columnName(header);
    if (!column) return;
    const field = (Object.keys(FIELDS) as Field[]).find((key) => FIELDS[key] === column.field);
    if (!field) return;
    const entry = columns.get(column.entity) ?? {};
    entry[field] = index;
    columns.set(column.entity, entry);
  });
  const entityNumbers = [...columns.keys()].sort((a, b) => a - b);
  for (const number of entityNumbers) {
    const entry = columns.get(number)!;
    for (const field of ['name', 'x', 'y', 'hdg'] as const) {
      if (entry[field] === undefined) throw new EsminiCsvError(`entity #${number} has no ${FIELDS[field]} column`, columnLine + 1);
    }
  }
  const rows: string[][] = [];
  let truncated = false;
  for (let index = columnLine + 1; index < lines.length; index++) {
    const line = lines[index];
    if (!line.trim()) continue;
    if (rows.length >= maxRows) {
      truncated = true;
      break;
    }
    const fields = line.split(',');
    // The last row may be cut short when esmini was stopped while writing it.
    if (fields.length < headers.length - 1) {
      if (index >= lines.length - 2) break;
      throw new EsminiCsvError(`expected ${headers.length - 1} fields, found ${fields.length}`, index + 1);
    }
    rows.push(fields);
  }
  const times = new Float64Array(rows.length);
  rows.forEach((row, index) => (times[index] = Number(row[1])));
  const number = (row: string[] | undefined, column: number | undefined, fallback: number) => {
    const value = row && column !== undefined ? Number(row[column]) : NaN;
    return Number.isFinite(value) ? value : fallback;
  };
  const entities = entityNumbers.map((entityNumber): EntityTrack => {
    const entry = columns.get(entityNumber)!;
    const series = (column: number | undefined) => Float64Array.from(rows, (row) => number(row, column, NaN));
    return {
      name: rows[0]?.[entry.name!]?.trim() ?? `#${entityNumber}`,
      length: number(rows[0], entry.length, 4.5),
      width: number(rows[0], entry.width, 1.8),
      centerX: number(rows[0], entry.centerX, 0),
      x: series(entry.x),
      y: series(entry.y),
      hdg: series(entry.hdg),
      speed: series(entry.speed),
    };
  });
  return { version: headerValue('esmini GIT REV:'), scenarioFile: headerValue('Scenario File Name:'), times, entities, truncated };
}

/** The road file esmini loaded, as its log says (`[] [info] Loaded OpenDRIVE: <path>`, ScenarioEngine.cpp); undefined when it loaded none. */
export function parseEsminiLoadedRoad(log: string): string | undefined {
  return /^\[[^\]]*\]\s*\[info\]\s*Loaded OpenDRIVE: (.+?)\s*$/m.exec(log)?.[1];
}
