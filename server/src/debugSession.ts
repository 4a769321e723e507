// The debug session's process (dist/debugSession.js, a bundle of its own): the adapter's child, started by the supervisor
// (debug/supervisor.ts) through dist/debugAdapter.js with SESSION_ARGUMENT. It runs the Debug Adapter Protocol over
// esmini's library; the supervisor, which only passes the protocol through, never loads this bundle.
import { DebugSession } from '@vscode/debugadapter';
import { reportProgressTo, ScenarioDebugSession } from './debug/adapter';
import { mapProgressPage } from './debug/progressPage';
import { progressWriter } from './debug/supervisor';

export function runSession(): void {
  const page = mapProgressPage();
  // The progress into the page shared with the supervisor where there is one (a store), else as lines to its pipe.
  reportProgressTo(page ? (progress) => page.progress(progress) : progressWriter(), page);
  DebugSession.run(ScenarioDebugSession);
}
