import { Problem, uniqueProblems } from '../problems';
import { ESMINI_FINDING_CHECKS, Evaluator, findingsToProblems, runChecks } from '../semantics';
import { concernsImporter, FlatSource } from './types';

/**
 * The esmini profile's findings (code `simulator`) of an analysis made for another simulator, as an analysis of the same
 * main for esmini gives them: each file the analysis read is checked again in esmini's context (esmini's reading of
 * values) from the semantics it built, without reading, parsing, resolving or linking anything again; an imported file's
 * findings count as `Flattener.build` counts its problems (`concernsImporter`: those of the groups imported).
 */
export function esminiFindingsOfAnalysis(source: FlatSource): Problem[] {
  const all = new Map<FlatSource, Problem[]>();
  const of = (each: FlatSource): Problem[] => {
    const known = all.get(each);
    if (known) return known;
    // A cycle's files are reached again before they are done: nothing more of them there.
    all.set(each, []);
    const semantics = each.semantics;
    const own = semantics
      ? findingsToProblems(
          semantics.ref,
          semantics.model.document,
          runChecks(
            { ...semantics, simulator: 'esmini', evaluator: new Evaluator(semantics.model, undefined, 'esmini') },
            ESMINI_FINDING_CHECKS,
          ),
        ).filter((problem) => problem.code === 'simulator')
      : [];
    const imported: Problem[] = [];
    for (const link of each.links) {
      if (!link.source) continue;
      const groupNames = link.info.groupReferences.map((groupReference) => groupReference.name);
      for (const problem of of(link.source)) if (concernsImporter(problem, link.source, groupNames)) imported.push(problem);
    }
    const problems = uniqueProblems([...own, ...imported]);
    all.set(each, problems);
    return problems;
  };
  return of(source);
}
