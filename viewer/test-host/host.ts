// A minimal MCP Apps host, as in the ext-apps basic-host example, for the browser tests.
// It renders the ui:// resource in a sandboxed iframe (srcdoc, CSP from the resource's
// _meta.ui.csp), speaks to it through the official AppBridge, and forwards the view's
// tools/call requests to the real MCP server through `window.hostCallTool`, a function
// the test process exposes (it holds a real MCP client session to `verigraph serve`).
import { AppBridge, PostMessageTransport } from "@modelcontextprotocol/ext-apps/app-bridge";

declare global {
  interface Window {
    hostCallTool: (name: string, args: unknown) => Promise<any>;
    showApp: (html: string, csp: Record<string, string[]> | undefined, toolName: string,
              args: Record<string, unknown>, result: any) => Promise<void>;
    hostLog: string[];
  }
}
window.hostLog = [];

function cspFor(csp: Record<string, string[]> | undefined): string {
  const list = (k: string) => (csp?.[k] ?? []).join(" ");
  return [`default-src 'none'`, `script-src 'unsafe-inline' ${list("resourceDomains")}`,
    `style-src 'unsafe-inline' ${list("resourceDomains")}`,
    `img-src data: ${list("resourceDomains")}`, `font-src ${list("resourceDomains") || "'none'"}`,
    `connect-src ${list("connectDomains") || "'none'"}`,
    `frame-src ${list("frameDomains") || "'none'"}`, `object-src 'none'`,
    `base-uri ${list("baseUriDomains") || "'none'"}`].join("; ");
}

window.showApp = async (html, csp, toolName, args, result) => {
  const iframe = document.getElementById("view") as HTMLIFrameElement;
  const policy = cspFor(csp);
  iframe.dataset.csp = policy;
  const withCsp = html.replace("<head>",
    `<head><meta http-equiv="Content-Security-Policy" content="${policy}">`);
  const bridge = new AppBridge(null, { name: "verigraph-test-host", version: "0.0.0" },
    { serverTools: {}, logging: {} },
    { hostContext: { theme: "light", displayMode: "inline", platform: "web",
                     toolInfo: { tool: { name: toolName, inputSchema: { type: "object" } } } } });
  bridge.onsizechange = ({ height }) => {  // flexible height: follow the view
    if (height) iframe.style.height = `${Math.ceil(height) + 4}px`;
  };
  bridge.oncalltool = async (params) => {
    window.hostLog.push(`tools/call ${params.name}`);
    return await window.hostCallTool(params.name, params.arguments ?? {});
  };
  const initialized = new Promise<void>((resolve) => { bridge.oninitialized = () => resolve(); });
  // Listen before the view loads: it sends ui/initialize as soon as its script runs.
  await bridge.connect(new PostMessageTransport(iframe.contentWindow!, iframe.contentWindow!));
  iframe.srcdoc = withCsp;
  await initialized;
  window.hostLog.push("initialized");
  await bridge.sendToolInput({ arguments: args });
  await bridge.sendToolResult(result);
  window.hostLog.push("tool-result sent");
};
