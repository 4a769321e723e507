import { defineDiagnostic, ProblemWording } from './definition';

/** What esmini 3.6 does with a LogicFile it does not find (ScenarioEngine.cpp, after `LocateFile`): it stops, exit code 255. */
export const ESMINI_ROAD_NOT_FOUND = 'esmini stops at such a scenario ("Failed to locate OpenDRIVE file")';

/** The folders a message names besides the scenario's own; the others are counted. */
const FOLDERS_NAMED = 3;

/**
 * A RoadNetwork LogicFile whose `filepath` (evaluated: `written`) is a file in none of `folders`, the scenario's folder
 * first, where a run has esmini look (core/semantics/roadFiles.ts `locateRoadFile`). `carlaTown`: it names a CARLA map.
 *
 * An error with `simulator = esmini`: esmini refuses the scenario (SPEC 12, a simulator the user targets). A warning
 * otherwise: the standard does not say where a simulator looks for the file, and a simulator's own search path (one
 * the check is not told of) may hold it (SPEC 11.6 leaves such a path as written). Never reported with
 * `simulator = carla`, whose own rule (profiles/carla.ts `roadFileMissing`) says where ScenarioRunner looks, and
 * never for a CARLA map's name unless esmini is the simulator: ScenarioRunner loads it by name, it is no file.
 */
export function roadFileWording(
  written: string,
  folders: readonly string[],
  severity: 'error' | 'warning',
  carlaTown: boolean,
  /**
   * Packages this file references that hold such a file (`RoadFileLookup.heldByReferencedPackages`): the package on disk
   * and the entries down to the file, a package stored inside it first when the package this file references is one.
   */
  heldBy: readonly { packageFile: string; entries: readonly string[]; referencedEntries?: number }[] = [],
  /** Packages this file references (on `line`, one-based) that could not be read, which may hold it (`RoadFileLookup.unreadReferencedPackages`). */
  unread: readonly { packageFile: string; line: number; reason: string }[] = [],
): ProblemWording<'road-file'> {
  const [own, ...all] = folders;
  const others = all.length > FOLDERS_NAMED ? [...all.slice(0, FOLDERS_NAMED), `${all.length - FOLDERS_NAMED} more folders`] : all;
  const where =
    others.length > 0 ? `found neither beside this file (${own}) nor in ${others.join(', ')}` : `not found beside this file (${own})`;
  const town = carlaTown ? `; '${written}' is a CARLA map, which esmini loads only from a file of that exact name` : '';
  return {
    severity,
    code: 'road-file',
    message: `road file '${written}' is ${where}${town}: ${ESMINI_ROAD_NOT_FOUND}`,
    hint:
      heldBy.length > 0
        ? heldInPackageHint(heldBy[0].packageFile, heldBy[0].entries, own, heldBy[0].referencedEntries ?? heldBy[0].entries.length - 1)
        : 'correct the path, or add the folder that holds the file to the road path (--road-path, the modular2simple.esmini.roadPath setting)' +
          unread
            .map(
              ({ packageFile, line, reason }) =>
                `; the package ${packageFile} this file references on line ${line} could not be read (${reason}), so whether it holds '${written}' is not known: repair it and check again`,
            )
            .join(''),
  };
}

/** A path or entry name as one word of a POSIX shell command: quoted when it holds anything but safe characters. */
function shellWord(text: string): string {
  return /^[\w@%+=:,./-]+$/.test(text) ? text : `'${text.replace(/'/g, `'\\''`)}'`;
}

/**
 * How to extract `entries`' last (a road file) from `packageFile` into `folder`. unzip reads no archive inside an archive, so
 * a package stored inside another (`entries` longer than one) is extracted first, each into a numbered folder of a new
 * temporary folder, so that no file of the user's is replaced; `-j` because esmini tries the path, then the file name.
 */
function heldInPackageHint(packageFile: string, entries: readonly string[], folder: string, referencedEntries: number): string {
  const file = entries[entries.length - 1];
  const packages = entries.slice(0, -1);
  const outside = 'but a file outside a package does not reach the files inside it';
  if (packages.length === 0)
    return `the package ${packageFile} this file references holds ${file}, ${outside}: extract it into ${folder} (a .mosc is a ZIP archive: unzip -j ${shellWord(packageFile)} ${shellWord(file)} -d ${shellWord(folder)}), or correct the path`;
  const steps: string[] = [];
  let archive = shellWord(packageFile);
  packages.forEach((inner, level) => {
    steps.push(`unzip -j ${archive} ${shellWord(inner)} -d ${level + 1}`);
    archive = shellWord(`${level + 1}/${inner.slice(inner.lastIndexOf('/') + 1)}`);
  });
  steps.push(`unzip -j ${archive} ${shellWord(file)} -d ${shellWord(folder)}`);
  // The package referenced (the one on disk, or one stored in it), then the packages stored in that one which hold the file.
  const named = (inner: readonly string[]) =>
    [...inner]
      .reverse()
      .map((each) => `'${each}'`)
      .join(' inside ');
  const referenced = packages.slice(0, referencedEntries);
  const below = packages.slice(referencedEntries);
  const which =
    referenced.length === 0
      ? `the package ${packageFile} this file references`
      : `the package ${named(referenced)} this file references, stored inside ${packageFile},`;
  const where = below.length === 0 ? `holds ${file}` : `holds ${file} in its package ${named(below)}`;
  return (
    `${which} ${where}, ${outside}: extract it into ${folder} ` +
    `(a .mosc is a ZIP archive, and unzip does not read one stored inside another, so extract the inner package first: ` +
    `cd "$(mktemp -d)" && ${steps.join(' && ')}), or correct the path`
  );
}

export const ROAD_FILE = defineDiagnostic({
  code: 'road-file',
  rule: { description: 'The road file a RoadNetwork LogicFile names is found where the simulator looks for it.' },
  severity: 'warning',
});
