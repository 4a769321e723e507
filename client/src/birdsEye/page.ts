/** The bird's-eye view's page: everything it loads is the bundled dist/birdsEye.js (no network, no CDN). */
export function birdsEyeHtml(cspSource: string, scriptUri: string, scriptNonce: string): string {
  return `<!DOCTYPE html><html><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src ${cspSource} data:; style-src 'unsafe-inline'; script-src 'nonce-${scriptNonce}';">
<style>
body{margin:0;padding:0;font-family:var(--vscode-font-family);font-size:var(--vscode-font-size);color:var(--vscode-foreground);display:flex;flex-direction:column;height:100vh;overflow:hidden}
#toolbar{display:flex;gap:6px;align-items:center;padding:4px 8px;flex-wrap:wrap;border-bottom:1px solid var(--vscode-panel-border)}
#title{font-weight:bold;margin-right:auto}
button{color:var(--vscode-button-foreground);background:var(--vscode-button-background);border:none;padding:3px 8px;cursor:pointer}
button:disabled{opacity:.5;cursor:default} #slider{width:180px}
#stage{position:relative;flex:1;min-height:120px;overflow:hidden} #canvas{position:absolute;left:0;top:0}
#tooltip{position:absolute;display:none;pointer-events:none;background:var(--vscode-editorHoverWidget-background);border:1px solid var(--vscode-editorHoverWidget-border);padding:2px 6px;white-space:nowrap}
#panel{max-height:34%;overflow:auto;padding:4px 8px;border-top:1px solid var(--vscode-panel-border)}
#entities{display:flex;gap:4px;flex-wrap:wrap;margin-bottom:4px} .entity,.event{background:var(--vscode-button-secondaryBackground);color:var(--vscode-button-secondaryForeground)}
#markers{position:relative;height:14px;background:var(--vscode-editorWidget-background);margin:4px 0}
.marker{position:absolute;top:1px;width:10px;height:10px;margin-left:-5px;border-radius:5px;cursor:pointer} .started{background:#ffca28} .planned{border:2px solid #ffca28;box-sizing:border-box}
#cursor{position:absolute;top:0;bottom:0;width:2px;background:var(--vscode-focusBorder)}
.never{opacity:.75} .running{background:var(--vscode-editor-stackFrameHighlightBackground,rgba(255,202,40,.25));font-weight:bold}
ul{margin:0;padding-left:16px} #problems{color:var(--vscode-editorWarning-foreground)} .error{color:var(--vscode-errorForeground)}
</style></head><body>
<div id="toolbar"><span id="title">loading…</span>
<button id="fit" title="Frame the entities where they are now">Entities</button><button id="network" title="Show the whole road network">Whole network</button><button id="load" title="Load an esmini --csv_logger CSV">Load run…</button><button id="compare" title="Load a second run (another concrete scenario), drawn dashed over the first">Compare run…</button><select id="compareMode" style="display:none" title="How the compared run is shown"><option value="overlay">overlaid (dashed)</option><option value="side">side by side</option></select>
<select id="follow" title="Follow an entity: keep it centred and plot its speed, gap and time to collision"></select>
<button id="play" disabled>Play run</button><input id="slider" type="range" min="0" max="1000" value="0" disabled><span id="time">no run loaded</span>
<button id="png">Save PNG</button><button id="svg">Save SVG</button></div>
<div id="stage"><canvas id="canvas"></canvas><div id="tooltip"></div></div>
<canvas id="plots" style="display:none;flex:none"></canvas>
<div id="panel"><div id="entities"></div><div id="markers"></div><ul id="events"></ul><ul id="problems"></ul></div>
<script nonce="${scriptNonce}" src="${scriptUri}"></script>
</body></html>`;
}
