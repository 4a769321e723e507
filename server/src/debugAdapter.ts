// The debug adapter's process entry (dist/debugAdapter.js): the Debug Adapter Protocol over stdin and stdout. As the
// editor starts it, it supervises (debug/supervisor.ts); its child, started with SESSION_ARGUMENT, is the session.
import { DebugSession } from '@vscode/debugadapter';
import { reportProgressTo, ScenarioDebugSession } from './debug/adapter';
import { mapProgressPage } from './debug/progressPage';
import { progressWriter, SESSION_ARGUMENT, superviseSession } from './debug/supervisor';

if (process.argv.includes(SESSION_ARGUMENT)) {
  const page = mapProgressPage();
  // The progress into the page shared with the supervisor where there is one (a store), else as lines to its pipe.
  reportProgressTo(page ? (progress) => page.progress(progress) : progressWriter(), page);
  DebugSession.run(ScenarioDebugSession);
} else superviseSession(process.argv[1]);
