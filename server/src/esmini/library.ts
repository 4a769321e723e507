import * as fs from 'node:fs';
import * as path from 'node:path';
import { projectEsminiFolder } from './locate';

/*
 * esmini's C library (libesminiLib.so, esminiLib.hpp), called from Node through the koffi FFI package: no C++ of
 * our own. ../shared/esmini/build.sh DEST installs it in DEST/lib beside DEST/bin/esmini; npm start, CI
 * (scripts/test-all.sh) and scripts/esminiBuild.mjs build into .cache/esmini, so the default is .cache/esmini/lib.
 * The library keeps one scenario per process (SE_Close before the next SE_Init).
 */

export const ESMINI_LIBRARY_FILE =
  process.platform === 'win32' ? 'esminiLib.dll' : process.platform === 'darwin' ? 'libesminiLib.dylib' : 'libesminiLib.so';

/** What to tell a user who has no esmini library. */
export const ESMINI_LIBRARY_MISSING_HELP =
  `esmini's library (${ESMINI_LIBRARY_FILE}) is built by ../shared/esmini/build.sh into .cache/esmini/lib of this project: ` +
  'run bash ../shared/esmini/build.sh .cache/esmini from the project root (npm start and npm run test:all do this), ' +
  'or set esminiLibrary in the launch configuration (the CLI: --esmini-library) to a libesminiLib.so or the folder holding it.';

export type LibraryLocation = { found: true; file: string } | { found: false; message: string };

/** The library: the configured file or folder (its `lib/` too), else `.cache/esmini/lib` of this project. */
export function locateEsminiLibrary(
  configured?: string,
  base: string = process.cwd(),
  projectBin = projectEsminiFolder(),
): LibraryLocation {
  if (configured && configured.trim()) {
    const resolved = path.resolve(base, configured.trim());
    const file = [resolved, path.join(resolved, ESMINI_LIBRARY_FILE), path.join(resolved, 'lib', ESMINI_LIBRARY_FILE)].find(isFile);
    if (file) return { found: true, file };
    return { found: false, message: `esmini's library is not at ${resolved}. ${ESMINI_LIBRARY_MISSING_HELP}` };
  }
  const built = projectBin ? path.join(path.dirname(projectBin), 'lib', ESMINI_LIBRARY_FILE) : undefined;
  if (built && isFile(built)) return { found: true, file: built };
  return { found: false, message: `esmini's library was not found${built ? ` at ${built}` : ''}. ${ESMINI_LIBRARY_MISSING_HELP}` };
}

function isFile(candidate: string): boolean {
  try {
    return fs.statSync(candidate).isFile();
  } catch {
    return false;
  }
}

/** SE_ScenarioObjectState (esminiLib.hpp), the fields read here. */
export interface EsminiObjectState {
  id: number;
  x: number;
  y: number;
  z: number;
  h: number;
  p: number;
  r: number;
  roadId: number;
  junctionId: number;
  t: number;
  laneId: number;
  laneOffset: number;
  s: number;
  speed: number;
  centerOffsetX: number;
  width: number;
  length: number;
}

export interface EsminiPositionDiff {
  ds: number;
  dt: number;
  dLaneId: number;
  dx: number;
  dy: number;
  oppositeLanes: boolean;
}

export type StoryboardCallback = (name: string, type: number, state: number, fullPath: string) => void;
export type ConditionCallback = (name: string, timestamp: number) => void;

/** The calls of esminiLib.hpp this project makes, typed. */
export interface EsminiLibrary {
  readonly file: string;
  addPath(folder: string): number;
  clearPaths(): void;
  setLogFilePath(file: string): void;
  logToConsole(on: boolean): void;
  setSeed(seed: number): void;
  initWithString(xml: string): number;
  stepDT(dt: number): void;
  close(): void;
  simulationTime(): number;
  quitFlag(): number;
  objectCount(): number;
  objectId(index: number): number;
  objectName(id: number): string;
  objectState(id: number): EsminiObjectState | undefined;
  objectAcceleration(id: number): number;
  distance(a: number, b: number, freeSpace: boolean): EsminiPositionDiff | undefined;
  /** TTC from a to b in seconds (a's coordinates, longitudinal, free space); undefined when esmini says none (-1). */
  timeToCollision(a: number, b: number): number | undefined;
  parameterNames(): { name: string; type: number }[];
  variableNames(): { name: string; type: number }[];
  /** A parameter's (or variable's) value read by its type (1 int, 2 double, 3 string, 4 bool: esminiLib's SE_ParameterType). */
  parameterValue(name: string, type: number): string | number | boolean | undefined;
  variableValue(name: string, type: number): string | number | boolean | undefined;
  onStoryboardChange(callback: StoryboardCallback): void;
  onCondition(callback: ConditionCallback): void;
  /** Flushes the C library's output streams (fflush(NULL)), so esmini's log file holds what it wrote so far. */
  flushLog(): void;
}

type KoffiModule = typeof import('koffi');

let loaded: EsminiLibrary | undefined;

/**
 * Loads the library once per process (esmini's state is global to it). Throws with `ESMINI_LIBRARY_MISSING_HELP` when it
 * is absent, and with the loader's reason when it does not load.
 */
export function loadEsminiLibrary(configured?: string, base?: string): EsminiLibrary {
  const location = locateEsminiLibrary(configured, base);
  if (!location.found) throw new EsminiLibraryError(location.message);
  if (loaded) {
    if (loaded.file !== location.file) throw new EsminiLibraryError(`esmini's library ${loaded.file} is already loaded in this process`);
    return loaded;
  }
  // Required here, not imported: koffi is a native module, loaded only by the processes that run a scenario.
  const koffi = require('koffi') as KoffiModule;
  let lib: ReturnType<KoffiModule['load']>;
  try {
    lib = koffi.load(location.file);
  } catch (error) {
    throw new EsminiLibraryError(
      `esmini's library ${location.file} does not load: ${(error as Error).message}. ${ESMINI_LIBRARY_MISSING_HELP}`,
    );
  }
  loaded = bind(koffi, lib, location.file);
  return loaded;
}

export class EsminiLibraryError extends Error {}

function bind(koffi: KoffiModule, lib: ReturnType<KoffiModule['load']>, file: string): EsminiLibrary {
  koffi.struct('SE_ScenarioObjectState', {
    id: 'int',
    model_id: 'int',
    ctrl_type: 'int',
    timestamp: 'double',
    x: 'double',
    y: 'double',
    z: 'double',
    h: 'double',
    p: 'double',
    r: 'double',
    roadId: 'uint32_t',
    junctionId: 'uint32_t',
    t: 'double',
    laneId: 'int',
    laneOffset: 'double',
    s: 'double',
    speed: 'double',
    centerOffsetX: 'double',
    centerOffsetY: 'double',
    centerOffsetZ: 'double',
    width: 'double',
    length: 'double',
    height: 'double',
    objectType: 'int',
    objectCategory: 'int',
    wheel_angle: 'double',
    wheel_rot: 'double',
    visibilityMask: 'int',
  });
  koffi.struct('SE_PositionDiff', {
    ds: 'double',
    dt: 'double',
    dLaneId: 'int',
    dx: 'double',
    dy: 'double',
    oppositeLanes: 'bool',
  });
  const StoryboardProto = koffi.proto('void SE_StoryboardCallback(const char *name, int type, int state, const char *full_path)');
  const ConditionProto = koffi.proto('void SE_ConditionCallback(const char *name, double timestamp)');
  const f = {
    addPath: lib.func('int SE_AddPath(const char *path)'),
    clearPaths: lib.func('void SE_ClearPaths()'),
    setLogFilePath: lib.func('void SE_SetLogFilePath(const char *path)'),
    logToConsole: lib.func('void SE_LogToConsole(bool mode)'),
    setSeed: lib.func('void SE_SetSeed(unsigned int seed)'),
    initWithString: lib.func('int SE_InitWithString(const char *xml, int disable_ctrls, int use_viewer, int threads, int record)'),
    // Its result (-1 with no scenario loaded) is not read: declared void, so that no JavaScript value is made for it at each step.
    stepDT: lib.func('void SE_StepDT(double dt)'),
    close: lib.func('void SE_Close()'),
    simulationTime: lib.func('double SE_GetSimulationTime()'),
    quitFlag: lib.func('int SE_GetQuitFlag()'),
    objectCount: lib.func('int SE_GetNumberOfObjects()'),
    objectId: lib.func('int SE_GetId(int index)'),
    objectName: lib.func('const char *SE_GetObjectName(int id)'),
    objectState: lib.func('int SE_GetObjectState(int id, _Out_ SE_ScenarioObjectState *state)'),
    objectAcceleration: lib.func('double SE_GetObjectAcceleration(int id)'),
    distance: lib.func('int SE_GetDistanceToObject(int a, int b, bool free_space, _Out_ SE_PositionDiff *diff)'),
    ttc: lib.func('int SE_GetTimeToCollision(int a, int b, int cs, int dist_type, bool free_space, _Out_ double *ttc)'),
    parameterCount: lib.func('int SE_GetNumberOfParameters()'),
    parameterName: lib.func('const char *SE_GetParameterName(int index, _Out_ int *type)'),
    variableCount: lib.func('int SE_GetNumberOfVariables()'),
    variableName: lib.func('const char *SE_GetVariableName(int index, _Out_ int *type)'),
    parameterInt: lib.func('int SE_GetParameterInt(const char *name, _Out_ int *value)'),
    parameterDouble: lib.func('int SE_GetParameterDouble(const char *name, _Out_ double *value)'),
    parameterString: lib.func('int SE_GetParameterString(const char *name, _Out_ const char **value)'),
    parameterBool: lib.func('int SE_GetParameterBool(const char *name, _Out_ bool *value)'),
    variableInt: lib.func('int SE_GetVariableInt(const char *name, _Out_ int *value)'),
    variableDouble: lib.func('int SE_GetVariableDouble(const char *name, _Out_ double *value)'),
    variableString: lib.func('int SE_GetVariableString(const char *name, _Out_ const char **value)'),
    variableBool: lib.func('int SE_GetVariableBool(const char *name, _Out_ bool *value)'),
    registerStoryboard: lib.func('void SE_RegisterStoryBoardElementStateChangeCallback(SE_StoryboardCallback *callback)'),
    registerCondition: lib.func('void SE_RegisterConditionCallback(SE_ConditionCallback *callback)'),
  };
  const libc = koffi.load(process.platform === 'darwin' ? 'libSystem.dylib' : 'libc.so.6');
  const fflush = libc.func('int fflush(void *stream)');
  // Registered callbacks live until unregistered; one of each is kept, replaced by the next registration.
  let storyboardHandle: unknown;
  let conditionHandle: unknown;
  const typedValue = (
    type: number,
    name: string,
    reads: { int: typeof f.parameterInt; double: typeof f.parameterDouble; string: typeof f.parameterString; bool: typeof f.parameterBool },
  ): string | number | boolean | undefined => {
    const out: [unknown] = [null];
    const read = type === 1 ? reads.int : type === 2 ? reads.double : type === 3 ? reads.string : type === 4 ? reads.bool : undefined;
    if (!read || (read(name, out) as number) < 0) return undefined;
    return out[0] as string | number | boolean;
  };
  const names = (count: () => unknown, nameOf: typeof f.parameterName) => {
    const listed: { name: string; type: number }[] = [];
    const total = count() as number;
    for (let index = 0; index < total; index++) {
      const type: [number] = [0];
      const name = nameOf(index, type) as string | null;
      if (name) listed.push({ name, type: type[0] });
    }
    return listed;
  };
  return {
    file,
    addPath: (folder) => f.addPath(folder) as number,
    clearPaths: () => void f.clearPaths(),
    setLogFilePath: (logFile) => void f.setLogFilePath(logFile),
    logToConsole: (on) => void f.logToConsole(on),
    setSeed: (seed) => void f.setSeed(seed),
    initWithString: (xml) => f.initWithString(xml, 0, 0, 0, 0) as number,
    stepDT: (dt) => void f.stepDT(dt),
    close: () => {
      f.close();
      for (const handle of [storyboardHandle, conditionHandle]) if (handle) koffi.unregister(handle as never);
      storyboardHandle = conditionHandle = undefined;
    },
    simulationTime: () => f.simulationTime() as number,
    quitFlag: () => f.quitFlag() as number,
    objectCount: () => f.objectCount() as number,
    objectId: (index) => f.objectId(index) as number,
    objectName: (id) => (f.objectName(id) as string | null) ?? `#${id}`,
    objectState: (id) => {
      const state = {} as EsminiObjectState;
      return (f.objectState(id, state) as number) < 0 ? undefined : state;
    },
    objectAcceleration: (id) => f.objectAcceleration(id) as number,
    distance: (a, b, freeSpace) => {
      const diff = {} as EsminiPositionDiff;
      return (f.distance(a, b, freeSpace, diff) as number) < 0 ? undefined : diff;
    },
    timeToCollision: (a, b) => {
      const ttc: [number] = [0];
      // cs 1: the entity's own coordinates (roadmanager::CoordinateSystem CS_ENTITY); dist_type 2: REL_DIST_LONGITUDINAL.
      if ((f.ttc(a, b, 1, 2, true, ttc) as number) < 0 || ttc[0] < 0) return undefined;
      return ttc[0];
    },
    parameterNames: () => names(f.parameterCount, f.parameterName),
    variableNames: () => names(f.variableCount, f.variableName),
    parameterValue: (name, type) =>
      typedValue(type, name, { int: f.parameterInt, double: f.parameterDouble, string: f.parameterString, bool: f.parameterBool }),
    variableValue: (name, type) =>
      typedValue(type, name, { int: f.variableInt, double: f.variableDouble, string: f.variableString, bool: f.variableBool }),
    onStoryboardChange: (callback) => {
      if (storyboardHandle) koffi.unregister(storyboardHandle as never);
      storyboardHandle = koffi.register(callback, koffi.pointer(StoryboardProto));
      f.registerStoryboard(storyboardHandle);
    },
    onCondition: (callback) => {
      if (conditionHandle) koffi.unregister(conditionHandle as never);
      conditionHandle = koffi.register(callback, koffi.pointer(ConditionProto));
      f.registerCondition(conditionHandle);
    },
    flushLog: () => void fflush(null),
  };
}
