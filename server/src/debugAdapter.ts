// The debug adapter's process entry (dist/debugAdapter.js): the Debug Adapter Protocol over stdin and stdout. As the
// editor starts it, it supervises (debug/supervisor.ts); its child, started with SESSION_ARGUMENT, is the session.
// The session is a bundle of its own (dist/debugSession.js), required only in the child: the supervisor starts without
// reading or running it, and the child is started that much sooner (docs/benchmarks.md, F5's first launch).
import { SESSION_ARGUMENT, superviseSession } from './debug/supervisor';

if (process.argv.includes(SESSION_ARGUMENT)) (require('./debugSession') as typeof import('./debugSession')).runSession();
else superviseSession(process.argv[1]);
