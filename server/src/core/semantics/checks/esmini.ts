import { esminiFactWording } from '../../diagnostics/simulator';
import { attribute, descendants } from '../../xml';
import { at } from './support';
import type { Finding, SemanticCheck } from './types';

/*
 * What esmini refuses (an error) or runs otherwise than written (a warning) beyond one element or attribute at a
 * time (those are the profile's tables, core/profiles/esmini.ts), each finding stating its fact's source lines.
 */

/** A SynchronizeAction's final AbsoluteSpeed of 0 or less followed by a steady state: esmini refuses it at load. */
export const esminiScenario: SemanticCheck = (context) => {
  const root = context.model.document.root;
  if (context.simulator !== 'esmini' || !root) return [];
  const findings: Finding[] = [];
  for (const speed of descendants(root)) {
    if (speed.name !== 'AbsoluteSpeed' || speed.parent?.name !== 'FinalSpeed' || speed.children.length === 0) continue;
    const value = attribute(speed, 'value');
    const text = value && context.evaluator.textOf(speed, value);
    // esmini compares with SMALL_NUMBER (1e-10); a value it cannot read is another check's.
    if (text === undefined || text.trim() === '' || !(Number(text) < 1e-10)) continue;
    findings.push({
      ...at(speed, value),
      ...esminiFactWording('steadyStateStop', `a final speed of ${text.trim()} with <${speed.children[0].name}>`),
    });
  }
  return findings;
};
