// Entry point. Three ways in, one renderer:
//  - an MCP App inside a chat client: talks to the host only through the ext-apps
//    bridge (App), and asks the server for the per-step view with the app-only tool;
//  - the page of `verigraph view`: a form posting to the local server;
//  - a `verigraph validate --html` report: the view is embedded in the file.
import { App } from "@modelcontextprotocol/ext-apps";
import { startPage } from "./page";
import type { EpisodeView } from "./types";
import { showView } from "./view";

export const VIEW_TOOL = "view_episode";
const root = document.getElementById("app")!;

function status(text: string, error = false): void {
  const p = document.createElement("p");
  p.className = error ? "status error" : "status";
  p.id = "status";
  p.textContent = text;
  root.replaceChildren(p);
}

// Which view a tool result asks for: the episode behind it, or the plan it checked.
function viewArguments(tool: string | undefined, args: Record<string, unknown>,
                       structured: Record<string, unknown> | undefined): Record<string, unknown> | null {
  if (tool === "validate_plan" || ("steps" in (structured ?? {}) && "plan" in args)) {
    const out: Record<string, unknown> = {};
    for (const k of ["plan", "scene_id", "graph", "episode_id", "goal"]) {
      if (args[k] !== undefined && args[k] !== null) out[k] = args[k];
    }
    return out;
  }
  const id = (structured?.episode_id ?? args.episode_id) as string | undefined;
  return id ? { episode_id: id } : null;
}

function startApp(): void {
  const app = new App({ name: "VeriGraph episode viewer", version: "0.1.0" });
  let input: Record<string, unknown> = {};
  app.ontoolinput = (params) => { input = (params.arguments ?? {}) as Record<string, unknown>; };
  app.ontoolresult = async (result) => {
    const tool = app.getHostContext()?.toolInfo?.tool?.name;
    const structured = result.structuredContent as Record<string, unknown> | undefined;
    const args = viewArguments(tool, input, structured);
    if (!args) { status("nothing to show: the result names no episode or plan"); return; }
    status("loading the per-step view…");
    try {
      const answer = await app.callServerTool({ name: VIEW_TOOL, arguments: args });
      if (answer.isError || !answer.structuredContent) {
        const text = answer.content?.map((c) => ("text" in c ? c.text : "")).join(" ");
        status(`the server could not build the view: ${text}`, true);
        return;
      }
      showView(root, answer.structuredContent as unknown as EpisodeView);
    } catch (err) {
      status(`the host refused the request: ${String(err)}`, true);
    }
  };
  app.connect().catch((err) => status(`could not reach the host: ${String(err)}`, true));
  status("waiting for a tool result…");
}

const embedded = document.getElementById("verigraph-data");
const mode = document.querySelector('meta[name="verigraph-mode"]')?.getAttribute("content");
if (embedded?.textContent) {
  showView(root, JSON.parse(embedded.textContent) as EpisodeView);
} else if (mode === "page") {
  startPage(root, (view) => showView(document.getElementById("result")!, view));
} else {
  startApp();
}
