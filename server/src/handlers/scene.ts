import { buildScene } from '../features/scene';
import { SceneRequest } from '../../../common/src/sceneProtocol';
import { request, ServerContext } from './context';

/** `modular2simple/scene`: what the bird's-eye view draws of a scenario. */
export function register(context: ServerContext): void {
  context.connection.onRequest(
    SceneRequest,
    request(context, SceneRequest.method, (params) => buildScene(context.workspace, context.roads, params)),
  );
}
