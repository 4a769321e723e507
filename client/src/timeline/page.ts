/** The storyboard timeline's page: everything it loads is the bundled dist/timeline.js (no network, no CDN). */
export function timelineHtml(cspSource: string, scriptUri: string, scriptNonce: string): string {
  return `<!DOCTYPE html><html><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src ${cspSource} data:; style-src 'unsafe-inline'; script-src 'nonce-${scriptNonce}';">
<style>
body{margin:0;padding:0;font-family:var(--vscode-font-family);font-size:var(--vscode-font-size);color:var(--vscode-foreground)}
#header{display:flex;gap:8px;align-items:center;padding:4px 8px;border-bottom:1px solid var(--vscode-panel-border);position:sticky;top:0;background:var(--vscode-editor-background);z-index:2}
#title{font-weight:bold;margin-right:auto;min-width:0;overflow:hidden;white-space:nowrap;text-overflow:ellipsis} #time{font-variant-numeric:tabular-nums;white-space:nowrap;flex:none}
#rows{position:relative;padding:0 8px 8px 8px}
.row{display:flex;align-items:flex-start;height:22px;border-bottom:1px solid var(--vscode-editorWidget-border,transparent)}
.label{width:34%;min-width:180px;box-sizing:border-box;flex:none;line-height:22px;overflow:hidden;white-space:nowrap;text-overflow:ellipsis;cursor:pointer}
.label:hover{text-decoration:underline} .kind{opacity:.65;margin-right:4px} .group{opacity:.65;margin-left:4px}
.track{position:relative;flex:1;height:100%;cursor:crosshair}
.bar{position:absolute;top:4px;height:14px;border-radius:3px;background:#42a5f5;min-width:2px}
.bar.Story{background:#7e57c2}.bar.Act{background:#5c6bc0}.bar.ManeuverGroup{background:#26a69a}.bar.Maneuver{background:#66bb6a}.bar.Event{background:#ffca28}.bar.Action{background:#ffa726}
.bar.open{border-right:2px dashed var(--vscode-foreground)}
.cause{position:absolute;font-size:10px;white-space:nowrap;overflow:hidden;text-overflow:ellipsis;box-sizing:border-box;color:var(--vscode-foreground);text-shadow:0 0 2px var(--vscode-editor-background)}
.never{font-size:11px;line-height:22px;color:var(--vscode-editorWarning-foreground);padding-left:4px;white-space:nowrap;overflow:hidden;text-overflow:ellipsis}
#axis{display:flex;height:18px;font-size:10px;opacity:.7} #axisLabels{position:relative;flex:1}
.axisLabel{position:absolute;white-space:nowrap;overflow:hidden;font-size:10px}
#cursor{position:absolute;top:0;bottom:0;width:2px;background:var(--vscode-focusBorder);pointer-events:none}
#empty{padding:8px;opacity:.8}
</style></head><body>
<div id="header"><span id="title">no trace loaded</span><span id="time"></span></div>
<div id="rows"></div>
<script nonce="${scriptNonce}" src="${scriptUri}"></script>
</body></html>`;
}
