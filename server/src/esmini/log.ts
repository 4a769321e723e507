/** One `[error]` or `[warn]` line of esmini's log. */
export interface EsminiLogMessage {
  level: 'error' | 'warn';
  /** Simulated time printed with it; undefined while the scenario is being loaded. */
  time: number | undefined;
  text: string;
  /** Zero-based line in the log. */
  logLine: number;
}

// esmini 3.6 CommonMini/logger.cpp prints `[<time>] [<level>] <message>`, the time empty while loading.
const LOG_LINE = /^\[([^\]]*)\] \[(error|warn)\] (.*)$/;

/** A kind of message esmini prints about its own road files or 3D models, never about the scenario run. */
export interface EsminiRemarkKind {
  pattern: RegExp;
  /** The esmini 3.6 source that prints it. */
  origin: string;
  /** Why it says nothing about the scenario. */
  why: string;
}

/**
 * What esmini 3.6 says in a headless run that is no problem of the scenario: no 3D models without a
 * viewer, and notes on what its road reader skips in a road file (esmini's sample roads have both).
 */
export const HARMLESS_REMARKS: readonly EsminiRemarkKind[] = [
  {
    pattern: /^3D model .* not located/,
    origin: 'CommonMini.cpp:330 LocateFile, for Entities.cpp:1936 Object::SetModel3DFullPath',
    why: 'a headless run draws no 3D models',
  },
  {
    pattern: /^scene graph file .* not located/,
    origin: 'CommonMini.cpp:330 LocateFile, for ScenarioEngine.cpp:523 (RoadNetwork/SceneGraphFile)',
    why: "a headless run draws no scene graph (the road's 3D model)",
  },
  {
    pattern: /^Unsupported geo reference attr: /,
    origin: 'RoadManager.cpp:7242 OpenDrive::ParseGeoLocalization',
    why: "a note on the road file's map projection, which a run does not use",
  },
  {
    pattern: /^Unsupported object type: /,
    origin: 'RoadManager.cpp:2992 RMObject::Str2Type (2974 RMObject::Type2Str)',
    why: 'a roadside object type of the road file that esmini reads as none; it does not take part in the run',
  },
];

/** Kept for callers that only filter: the patterns of HARMLESS_REMARKS. */
export const HARMLESS_MESSAGES: readonly RegExp[] = HARMLESS_REMARKS.map((remark) => remark.pattern);

/** A harmless remark as esmini printed it, counted once per text. */
export interface EsminiRemark {
  level: 'error' | 'warn';
  text: string;
  /** Zero-based line of its first occurrence in the log. */
  logLine: number;
  count: number;
  origin: string;
  why: string;
}

export interface EsminiLog {
  /** What may be about the scenario: to be placed on its source lines. */
  messages: EsminiLogMessage[];
  /** What is about esmini's own files (HARMLESS_REMARKS): information, never a problem of the scenario. */
  remarks: EsminiRemark[];
}

/** esmini's `[error]` and `[warn]` lines, the harmless remarks apart. */
export function readEsminiLog(output: string): EsminiLog {
  const messages: EsminiLogMessage[] = [];
  const remarks = new Map<string, EsminiRemark>();
  const lines = output.split(/\r?\n/);
  for (let index = 0; index < lines.length; index++) {
    const match = LOG_LINE.exec(lines[index]);
    if (!match) continue;
    // A fatal error comes as "Exception: <message>", after its own line when it had one ("Exception: [] [error] <message>").
    const level = match[2] as 'error' | 'warn';
    // Some messages repeat their level ("[warn] Warning: Controller ... operating domains"): the severity says it once.
    const text = match[3]
      .replace(/^Exception: (\[[^\]]*\] \[\w+\] )?/, '')
      .replace(level === 'warn' ? /^Warning: / : /^Error: /, '')
      .trim();
    const remark = HARMLESS_REMARKS.find((kind) => kind.pattern.test(text));
    if (remark) {
      const known = remarks.get(text);
      if (known) known.count++;
      else remarks.set(text, { level, text, logLine: index, count: 1, origin: remark.origin, why: remark.why });
      continue;
    }
    messages.push({ level, time: match[1] === '' ? undefined : Number(match[1]), text, logLine: index });
  }
  return { messages, remarks: [...remarks.values()] };
}

/** esmini's `[error]` and `[warn]` lines that may be about the scenario (the harmless remarks left out). */
export function parseEsminiLog(output: string): EsminiLogMessage[] {
  return readEsminiLog(output).messages;
}

/** A collision esmini's global detection (`--collision`) logged: `Collision between A and B` (esmini 3.6, ScenarioEngine.cpp:1160 DetectCollisions). */
export interface Collision {
  entities: [string, string];
  time: number | undefined;
}

const COLLISION = /^Collision between (.+) and (.+?)$/;

/** The collision a log line says began (never the line saying that it `dissolved`, ScenarioEngine.cpp:1170). */
export function collisionOf(message: Pick<EsminiLogMessage, 'text' | 'time'>): Collision | undefined {
  if (isCollisionEnd(message.text)) return undefined;
  const match = COLLISION.exec(message.text);
  return match ? { entities: [match[1], match[2]], time: message.time } : undefined;
}

/** Each collision esmini logged as it began. */
export function collisionsIn(messages: readonly EsminiLogMessage[]): Collision[] {
  return messages.flatMap((message) => collisionOf(message) ?? []);
}

/** esmini's word that two entities' bounding boxes no longer overlap: the end of a collision, no problem of its own. */
export function isCollisionEnd(text: string): boolean {
  return text.startsWith('Collision between ') && text.endsWith(' dissolved');
}

/**
 * Whether a collision esmini logged is one the scenario did not mean: two entities the Init placed on each other (at or
 * before time 0: a load on a truck, two cars compared on one spot), a vehicle and the trailer esmini made of its
 * Trailer (named NAME+, Entities.cpp:1553) or one the scenario hitches to it (`hitched`), or a ghost esmini made
 * (NAME_ghost, ScenarioEngine.cpp:968), which nothing can hit.
 */
export function isMeantOverlap(collision: Collision, declared: ReadonlySet<string>, hitched: ReadonlySet<string>): boolean {
  const [a, b] = collision.entities;
  if (collision.time === undefined || collision.time <= 0) return true;
  if (a === `${b}+` || b === `${a}+` || hitched.has(`${a}\u0000${b}`) || hitched.has(`${b}\u0000${a}`)) return true;
  return [a, b].some((name) => name.endsWith('_ghost') && !declared.has(name));
}
