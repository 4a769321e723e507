import * as path from 'node:path';
import { CARLA_TOWNS } from '../profiles/scenarioRunner';
import { schemaFindingWords } from '../diagnostics/schemaFindings';
import { checkSchema } from '../schema/validate';
import { diskRef, ScenarioStore, SourceRef } from '../sources';
import { XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { CatalogFile, CatalogLoader } from './catalogs';
import { SemanticModel } from './model';
import { coreMemo } from '../memos';

/**
 * The files CARLA's ScenarioRunner reads beside a scenario, found as it finds them (its
 * openscenario_configuration.py `_load_catalogs` and `_set_carla_town`): no SCENARIO_PATH, no
 * `$parameter` resolved in a path, a catalog only as `<Directory path>/<Type>Catalog.xosc`.
 */

/** One `<Type>Catalog` location of the scenario and the file ScenarioRunner reads for it. */
export interface CarlaCatalogLocation {
  /** `Vehicle`, `Controller`, ... */
  type: string;
  location: XmlElement;
  pathAttribute: XmlAttribute | undefined;
  /** The file it reads, absolute. */
  file: string;
  /** The catalog in that file; undefined when there is none (ScenarioRunner then warns and reads nothing). */
  catalog: CatalogFile | undefined;
  /** The first errors of that file against the 1.0 schema ScenarioRunner validates it with (line: message). */
  schemaErrors: string[];
}

export interface CarlaRoad {
  /** The LogicFile element and its filepath as written (ScenarioRunner uses the last one). */
  element: XmlElement;
  attribute: XmlAttribute;
  /** For an `.xodr`: the absolute path and whether it is a file. */
  xodr?: { file: string; exists: boolean };
  /** For any other name: whether it is a CARLA map. */
  town?: { known: boolean };
}

export interface CarlaFiles {
  catalogs: CarlaCatalogLocation[];
  /** Undefined when the scenario has no RoadNetwork/LogicFile. */
  road: CarlaRoad | undefined;
}

/** A catalog file's errors against the 1.0 schema, once per modelled catalog (catalogs are modelled once per text). */
const schemaErrorsOf = coreMemo<CatalogFile, string[]>('carlaCatalogSchemaErrors');
const SCHEMA_ERRORS_KEPT = 3;

function catalogSchemaErrors(file: CatalogFile): string[] {
  let errors = schemaErrorsOf.get(file);
  if (!errors) {
    const document = file.model.document;
    errors = checkSchema(document, { modular: false, version: '1.0' })
      .findings.filter((finding) => finding.severity === 'error')
      .slice(0, SCHEMA_ERRORS_KEPT)
      .map((finding) => `line ${document.lines.positionAt(finding.element.start).line + 1}: ${schemaFindingWords(finding).message}`);
    schemaErrorsOf.set(file, errors);
  }
  return errors;
}

function lastLogicFile(document: XmlDocument): { element: XmlElement; attribute: XmlAttribute } | undefined {
  const network = document.root?.children.find((child) => child.name === 'RoadNetwork');
  const files = network?.children.filter((child) => child.name === 'LogicFile') ?? [];
  for (const element of files.reverse()) {
    const attribute = element.attributes.find((candidate) => candidate.name === 'filepath');
    if (attribute) return { element, attribute };
  }
  return undefined;
}

/** What ScenarioRunner reads beside a scenario on disk; undefined for a catalog file or a file inside a package (it reads neither). */
export async function carlaFilesOf(
  store: ScenarioStore,
  loader: CatalogLoader,
  ref: SourceRef,
  model: SemanticModel,
): Promise<CarlaFiles | undefined> {
  if (ref.entries.length > 0 || model.catalog || !model.document.root) return undefined;
  const folder = path.dirname(path.resolve(ref.disk));
  const catalogs: CarlaCatalogLocation[] = [];
  for (const location of model.catalogLocations) {
    const type = location.kind.replace(/Catalog$/, '');
    const written = location.pathAttribute?.value ?? '';
    const joined = `${written}/${type}Catalog.xosc`;
    const file = path.isAbsolute(joined) ? joined : path.join(folder, joined);
    const catalog = (await store.kindOf(file)) === 'file' ? await loader.file(diskRef(file)) : undefined;
    catalogs.push({
      type,
      location: location.directory.parent ?? location.directory,
      pathAttribute: location.pathAttribute,
      file,
      catalog,
      schemaErrors: catalog ? catalogSchemaErrors(catalog) : [],
    });
  }
  const logic = lastLogicFile(model.document);
  let road: CarlaRoad | undefined;
  if (logic) {
    const written = logic.attribute.value;
    if (written.includes('.xodr')) {
      const file = path.isAbsolute(written) ? written : `${folder}/${written}`;
      road = { ...logic, xodr: { file, exists: (await store.kindOf(file)) === 'file' } };
    } else {
      road = { ...logic, town: { known: CARLA_TOWNS.includes(written) } };
    }
  }
  return { catalogs, road };
}
