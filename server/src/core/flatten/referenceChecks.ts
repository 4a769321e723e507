import { Problem } from '../problems';
import { SchemaVersionSetting } from '../schema/version';
import { linksOfParse, ReferenceCheckResults } from './carriedLinks';
import { entityContextOf, referenceEntityProblems } from './checks';
import { overrideContextOf, referenceOverrideProblems } from './outputSchema';
import { FlatSource } from './types';

/**
 * The analysis's checks of a main file's references besides linking them: imported groups naming entities the main
 * file does not declare, override values that do not fit their attribute. A reference whose link an edit inside one
 * value carried over takes its previous results, placed in the edited text (`linksOfParse`), when what they read
 * outside it is as it was: the entities declared and the schema version, and no parameter of the main file.
 */
export function referenceChecks(
  source: FlatSource,
  schemaVersion: SchemaVersionSetting | 'off',
): { entity: Problem[]; override: Problem[] } {
  const entityContext = entityContextOf(source);
  const overrideContext = schemaVersion === 'off' ? undefined : overrideContextOf(source, { version: schemaVersion });
  if (!entityContext) return { entity: [], override: [] };
  const chosen = overrideContext?.chosen;
  const context = [
    schemaVersion,
    chosen ? `${chosen.version} ${chosen.stated} ${chosen.fallback}` : '',
    entityContext.main ? 'evaluated' : 'written',
    ...entityContext.declared,
  ].join('\n');
  const parseLinks = source.original ? linksOfParse(source.original.document, source.links) : undefined;
  const known = parseLinks?.checks?.context === context ? parseLinks.checks.results : [];
  const results: (ReferenceCheckResults | undefined)[] = [];
  const entity: Problem[] = [];
  const override: Problem[] = [];
  for (const [index, link] of source.links.entries()) {
    let checked = known[index];
    if (!checked) {
      const entities = referenceEntityProblems(source, link, entityContext);
      const overrides = overrideContext
        ? referenceOverrideProblems(source, link, overrideContext)
        : { problems: [], readsParameters: false };
      checked = { entity: entities.problems, override: overrides.problems };
      // Results that read a parameter of the main file are made again: an edit elsewhere may have changed its value.
      const carriable =
        !entities.readsParameters && !overrides.readsParameters && ![...entities.problems, ...overrides.problems].some((p) => p.related);
      results.push(carriable ? checked : undefined);
    } else {
      results.push(checked);
    }
    entity.push(...checked.entity);
    override.push(...checked.override);
  }
  if (parseLinks) parseLinks.checks = { context, results };
  return { entity, override };
}
