/**
 * After *Insert into Main*: the main run headless in esmini, and a notice naming the scripted actors that touch. It
 * never holds the edit back: the insert is done before the run starts, and a run that cannot happen is only logged.
 */
import { secondsText } from '../../../common/src/collisions';
import type { LibraryCollisionsResult } from '../../../common/src/libraryProtocol';

/** At most this many collisions are named; the rest are counted. */
const NAMED = 3;

/** The notice for a run's collisions between scripted actors, or undefined when there is none (or no run). */
export function collisionNotice(moduleName: string, result: LibraryCollisionsResult): string | undefined {
  if (!result.ran || result.collisions.length === 0) return undefined;
  const named = result.collisions
    .slice(0, NAMED)
    .map(({ entities, time }) => `${entities[0]} and ${entities[1]} at ${secondsText(time)} s`);
  const more = result.collisions.length - named.length;
  return `After inserting library:${moduleName}, esmini's run has scripted actors touch: ${named.join(', ')}${
    more > 0 ? ` and ${more} more` : ''
  }. A scripted car neither brakes nor steers for another: move one, or change its speed or trigger (docs/library.md).`;
}
