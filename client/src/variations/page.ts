/** The Variations view's page: everything it loads is the bundled dist/variations.js (no network, no CDN). */
export function variationsHtml(cspSource: string, scriptUri: string, scriptNonce: string): string {
  return `<!DOCTYPE html><html><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src ${cspSource} data:; style-src 'unsafe-inline'; script-src 'nonce-${scriptNonce}';">
<style>
body{margin:0;padding:0;font-family:var(--vscode-font-family);font-size:var(--vscode-font-size);color:var(--vscode-foreground);display:flex;flex-direction:column;height:100vh;overflow:hidden}
#toolbar{display:flex;gap:8px;align-items:center;padding:4px 8px;flex-wrap:wrap;border-bottom:1px solid var(--vscode-panel-border)}
#title{font-weight:bold;margin-right:auto}
select{color:var(--vscode-dropdown-foreground);background:var(--vscode-dropdown-background);border:1px solid var(--vscode-dropdown-border)}
button{font:inherit;color:var(--vscode-button-secondaryForeground);background:var(--vscode-button-secondaryBackground);border:none;padding:2px 8px;cursor:pointer}
button.outcome{display:inline-flex;align-items:center;gap:4px} button.outcome[aria-pressed=false]{opacity:.45;text-decoration:line-through}
.swatch{display:inline-block;width:10px;height:10px;border-radius:5px}
th button.sort{background:none;color:inherit;font-weight:bold;padding:0;width:100%;text-align:right}
#main{flex:1;display:flex;flex-direction:column;overflow:hidden}
#plot{flex:0 0 auto;padding:4px 8px} #plot circle.point{cursor:pointer} #plot circle.selected{stroke-width:3;stroke-opacity:1}
#tableArea{flex:1;overflow:auto;padding:0 8px 8px}
table.results{border-collapse:collapse} th,td{border:1px solid var(--vscode-panel-border);padding:1px 8px;text-align:right;white-space:nowrap}
th.reason,td.reason{text-align:left;white-space:normal;min-width:16em} th.reason button.sort{text-align:left}
th{position:sticky;top:0;background:var(--vscode-editorWidget-background);cursor:pointer;user-select:none}
tbody tr{cursor:pointer} tbody tr:hover{background:var(--vscode-list-hoverBackground)}
tbody tr.selected,tbody tr.selected:hover{background:var(--vscode-list-activeSelectionBackground,#04395e);color:var(--vscode-list-activeSelectionForeground,#ffffff);outline:2px solid var(--vscode-focusBorder,#007fd4);outline-offset:-2px}
tbody tr.selected a.open{color:inherit;font-weight:bold}
a.open{color:var(--vscode-textLink-foreground)}
#note,#summary{opacity:.8} .error,#notice{color:var(--vscode-errorForeground)}
</style></head><body>
<div id="toolbar"><span id="title">loading…</span><span id="filters"></span>
<label>x <select id="xAxis"></select></label><label>y <select id="yAxis"></select></label></div>
<div id="main"><div id="summary"></div><div id="notice" role="status"></div><div id="plot"></div><div id="tableArea"><div id="note"></div><div id="table"></div></div></div>
<script nonce="${scriptNonce}" src="${scriptUri}"></script>
</body></html>`;
}
