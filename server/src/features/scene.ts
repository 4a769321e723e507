import { ResponseError } from 'vscode-languageserver/node';
import { elementPlace } from '../analysis';
import { FlatSource } from '../core/flatten';
import { MAX_ROAD_FILE_BYTES, parseOpenDrive, RoadNetwork } from '../core/opendrive/road';
import { sampleNetwork } from '../core/opendrive/sample';
import { foundRoadName, logicFileOf, readFoundRoad, roadFolders, scenarioFolderOf } from '../core/semantics/roadFiles';
import { scenarioScene } from '../core/scene';
import { analyzeDocument } from '../core/semantics';
import { baseName, displayRef, nodeFileSystem } from '../core/sources';
import { decodeUtf8 } from '../core/text';
import { attributeValue, XmlElement } from '../core/xml';
import { RunTraceParams, SceneParams, SceneResult, SourceLocation } from '../../../common/src/sceneProtocol';
import type { TraceRecord } from '../../../common/src/trace';
import { originOf } from '../core/flatten';
import { esminiFolders } from '../esmini/run';
import { storyboardMapOf, traceFromLog } from '../esmini/storyboardTrace';
import type { SectionPolylines } from '../../../common/src/sectionPolylines';
import { Workspace } from '../workspace';
import { SERVER_MEMOS } from '../database';

/** Road files are large and rarely change: the sampled network is kept per path, size and content. */
interface CachedNetwork {
  text: string;
  network: RoadNetwork;
  sections: SectionPolylines[];
  roadCount: number;
  problems: string[];
}
const NETWORK_CACHE_SIZE = SERVER_MEMOS.roadNetworks.bound.entries;

/** The sampled road networks of one server, the most recently used few, each kept while its text is unchanged. */
export class RoadNetworkCache {
  private readonly networks = new Map<string, CachedNetwork>();

  load(filePath: string, text: string): CachedNetwork {
    const cached = this.networks.get(filePath);
    if (cached && cached.text === text) return cached;
    const network = parseOpenDrive(text);
    const entry: CachedNetwork = {
      text,
      network,
      sections: sampleNetwork(network),
      roadCount: network.roads.length,
      problems: network.problems.slice(0, 10).map((problem) => `${filePath}: ${problem.message}`),
    };
    this.networks.delete(filePath);
    this.networks.set(filePath, entry);
    while (this.networks.size > NETWORK_CACHE_SIZE) this.networks.delete(this.networks.keys().next().value as string);
    return entry;
  }
}

function locationOf(
  workspace: Workspace,
  source: FlatSource,
  element: XmlElement | undefined,
  attributeName = 'name',
): SourceLocation | undefined {
  const place = element ? elementPlace(source, element, attributeName) : undefined;
  return place ? { uri: workspace.uriOf(place.ref), line: place.range.start.line, character: place.range.start.character } : undefined;
}

/** The scene of a scenario: its road network sampled, entities at their start, its events. */
export async function buildScene(workspace: Workspace, roads: RoadNetworkCache, params: SceneParams): Promise<SceneResult> {
  const ref = await workspace.uris.toRef(params.uri);
  if (!ref) throw new ResponseError(-32602, `not a scenario URI: ${params.uri}`);
  // Rendered: a main file is shown as it runs, flattened.
  const source = workspace.flattener().rendered(await workspace.source(ref));
  const model = source.model ?? source.original;
  if (!model?.document.root) throw new ResponseError(-32602, `${displayRef(ref, workspace.folders[0])} could not be read as a scenario`);
  const problems: string[] = [];
  if (!source.model && source.original && source.links.length > 0)
    problems.push('the scenario could not be flattened; the view shows the file as written, without the groups it imports');

  // The road file is needed before positions can be evaluated: the one Run in esmini hands esmini, in the folders it hands esmini (esmini/run.ts esminiFolders).
  const folders = roadFolders(params.roadPath, workspace.folders[0] ?? scenarioFolderOf(ref));
  const { road } = await esminiFolders(workspace.flattener(), ref, source, folders);
  // Places are found from the document shown (the flattened one for a main file).
  const shownLogic = logicFileOf(model.document);
  let network: RoadNetwork | undefined;
  let sections: SectionPolylines[] = [];
  let roadFile: SceneResult['roadFile'];
  if (road) {
    // A file on disk, or the entry of the scenario's package that a run writes beside the flattened scenario.
    const resolved = foundRoadName(road);
    const filepath = road.logic.filepath;
    roadFile = { filepath, resolved, roadCount: 0, source: locationOf(workspace, source, shownLogic?.element, 'filepath') };
    if (!resolved) {
      problems.push(
        `road file "${filepath}" not found; looked for ${road.candidates.join(', ')}. Add its folder to the setting modular2simple.esmini.roadPath.`,
      );
    } else {
      // Read fresh from disk (a road file may change), bounded, and refused when not a regular file (a FIFO, a device), so that a road file never hangs the server.
      const read = await readFoundRoad(workspace.store, road, MAX_ROAD_FILE_BYTES, nodeFileSystem).then(
        (bytes) => ({ bytes, error: undefined }),
        (error: Error) => ({ bytes: undefined, error: error.message }),
      );
      const bytes = read.bytes;
      if (read.error) problems.push(`road file ${resolved} could not be read: ${read.error}`);
      else if (!bytes) problems.push(`road file ${resolved} could not be read`);
      else if (bytes.byteLength > MAX_ROAD_FILE_BYTES)
        problems.push(`road file ${resolved} is larger than ${MAX_ROAD_FILE_BYTES / 1024 / 1024} MB; not drawn`);
      else {
        const text = decodeUtf8(bytes);
        const loaded = roads.load(resolved, text);
        network = loaded.network;
        sections = loaded.sections;
        roadFile.roadCount = loaded.roadCount;
        problems.push(...loaded.problems);
      }
    }
  } else {
    problems.push('the scenario names no RoadNetwork/LogicFile; entities are drawn without roads');
  }

  // Routes named through catalogs are found by the semantics of the document shown (a flattened text is analysed afresh).
  const semantics =
    source.semantics?.model.document === model.document
      ? source.semantics
      : await analyzeDocument(ref, model.document, workspace.flattener().catalogs, false);
  const scene = scenarioScene(model.document, network, semantics);
  // esmini's path of each event (the key of its start in a trace: one per copy of a reused group), from the map Run in esmini reads its log with.
  const map = source.model ? storyboardMapOf(source) : undefined;
  const paths = new Map(map?.elements.filter((element) => element.kind === 'Event').map((element) => [element.element, element.path]));
  for (const entity of scene.entities) if (entity.problem) problems.push(`${entity.name}: ${entity.problem}`);
  return {
    uri: params.uri,
    title: baseName(ref),
    roadFile,
    sections,
    entities: scene.entities.map((entity) => ({
      name: entity.name,
      kind: entity.kind,
      length: entity.length,
      width: entity.width,
      centerX: entity.centerX,
      x: entity.x,
      y: entity.y,
      hdg: entity.hdg,
      described: entity.described,
      problem: entity.problem,
      source: locationOf(workspace, source, entity.position ?? entity.declaration, entity.position ? 'none' : 'name'),
    })),
    events: scene.events.map((event) => {
      const origin = originOf(source, event.groupElement);
      const copied = origin.source !== source;
      return {
        name: event.name,
        maneuver: event.maneuver,
        group: event.group,
        act: event.act,
        trigger: event.trigger,
        plannedTime: event.plannedTime,
        source: locationOf(workspace, source, event.element),
        path: paths.get(event.element),
        actors: event.actors,
        ...(copied ? { sourceGroup: { name: attributeValue(origin.element, 'name') ?? '', file: baseName(origin.source.ref) } } : {}),
      };
    }),
    problems,
  };
}

/** The storyboard trace of a run of esmini's program on the scenario at `uri`, read from its log as Run in esmini reads it. */
export async function runTrace(workspace: Workspace, params: RunTraceParams): Promise<TraceRecord[]> {
  const ref = await workspace.uris.toRef(params.uri);
  if (!ref) throw new ResponseError(-32602, `not a scenario URI: ${params.uri}`);
  if (typeof params.log !== 'string') throw new ResponseError(-32602, "runTrace needs the run's log text");
  const source = workspace.flattener().rendered(await workspace.source(ref));
  if (!source.model)
    throw new ResponseError(
      -32602,
      `${displayRef(ref, workspace.folders[0])} could not be flattened, so its run's log cannot be placed on its elements`,
    );
  return traceFromLog(storyboardMapOf(source), params.log);
}
