// The debug adapter's process entry (dist/debugAdapter.js): the Debug Adapter Protocol over stdin and stdout.
import { DebugSession } from '@vscode/debugadapter';
import { ScenarioDebugSession } from './debug/adapter';

DebugSession.run(ScenarioDebugSession);
