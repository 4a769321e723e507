// The debug adapter's process entry (dist/debugAdapter.js): the Debug Adapter Protocol over stdin and stdout. As the
// editor starts it, it supervises (debug/supervisor.ts); its child, started with SESSION_ARGUMENT, is the session.
import { DebugSession } from '@vscode/debugadapter';
import { reportProgressTo, ScenarioDebugSession } from './debug/adapter';
import { mapProgressPage } from './debug/progressPage';
import { progressWriter, SESSION_ARGUMENT, superviseSession } from './debug/supervisor';

if (process.argv.includes(SESSION_ARGUMENT)) {
  reportProgressTo(progressWriter(), mapProgressPage());
  DebugSession.run(ScenarioDebugSession);
} else superviseSession(process.argv[1]);
