import { AnalysisResult, Flattener } from '../../server/src/core/flatten';
import { DEFAULT_CARLA_RELEASE } from '../../server/src/core/profiles/simulators';
import { SchemaCheckMemory } from '../../server/src/core/schema/problems';
import { refId, ScenarioStore, SourceRef } from '../../server/src/core/sources';
import { ReusingFlattener, SharedSources } from '../../server/src/sharedSources';
import { SourceDependencies } from '../../server/src/sourceDependencies';

/**
 * A folder analysed as the server's database does across edits: one store, one flattener per generation reusing
 * the sources of the last, the edited file forgotten between them; and the same text analysed afresh.
 */
export function editorGenerations(root: string) {
  const store = new ScenarioStore({ scenarioPath: [], root });
  const shared = new SharedSources(64 * 1024 * 1024, () => new Set());
  const memory = new SchemaCheckMemory();
  return {
    store,
    generation: () =>
      new ReusingFlattener(
        store,
        shared,
        new SourceDependencies(),
        'asam',
        { version: 'auto' },
        memory,
        () => undefined,
        DEFAULT_CARLA_RELEASE,
      ),
    /** The editor's text of a file, read by the next generation. */
    edited(ref: SourceRef, text: string): void {
      store.setOverlay(ref, text);
      shared.delete(refId(ref));
    },
    /** The analysis of `text` as `ref` by a new store and flattener, nothing carried. */
    fresh(ref: SourceRef, text: string): Promise<AnalysisResult> {
      const freshStore = new ScenarioStore({ scenarioPath: [], root });
      freshStore.setOverlay(ref, text);
      return new Flattener(freshStore, 'asam', { version: 'auto' }).analyze(ref);
    },
  };
}
