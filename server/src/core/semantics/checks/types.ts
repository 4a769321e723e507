/** What a semantic check is given and what it reports: shared by checks.ts, the checks of checks/ and networkChecks.ts. */
import type { Problem } from '../../problems';
import type { CarlaRelease, Simulator } from '../../profiles/simulators';
import type { CarlaFiles } from '../carlaFiles';
import type { SourceRef } from '../../sources';
import type { XmlAttribute, XmlElement } from '../../xml';
import type { CatalogResolution } from '../catalogs';
import type { Evaluator, SemanticModel } from '../model';
import type { RoadSignals } from '../roadNetwork';
import type { RoadFileLookup } from '../roadFiles';

export interface SemanticContext {
  ref: SourceRef;
  model: SemanticModel;
  evaluator: Evaluator;
  catalogs: CatalogResolution;
  /**
   * True for a modular main file, whose storyboard names are only known once it is flattened; the
   * flattened output is checked for them instead.
   */
  modular: boolean;
  /** The simulator whose known gaps are checked (core/profiles); absent or `asam`: none. */
  simulator?: Simulator;
  /** With `simulator` = `carla`: the ScenarioRunner release whose facts apply (0.9.16 when absent). */
  carlaRelease?: CarlaRelease;
  /** With `simulator` = `carla`: the catalog and road files ScenarioRunner reads beside the scenario, as it finds them. */
  carlaFiles?: CarlaFiles;
  /** The road file the document's LogicFile names, looked for where a run has esmini look; absent when it names none or a parameter of unknown value. */
  roadFile?: RoadFileLookup;
  /** The signals of the road file the document names; absent when it names none or it cannot be read (the road rules are then skipped). */
  road?: RoadSignals;
}

/** A problem at document offsets, before it is given a file and a range (`problemOfFinding`). */
export interface Finding extends Omit<Problem, 'source' | 'range'> {
  element: XmlElement;
  /** The attribute the offsets lie in, when they do (for mapping an output position to its source). */
  attribute: XmlAttribute | undefined;
  start: number;
  end: number;
}

export type SemanticCheck = (context: SemanticContext) => Finding[];
