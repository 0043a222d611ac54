// The official TypeScript SDK as a client of `verigraph serve`, with ajv in strict mode
// checking every tool's input and output schema and every structured result.
//
//   node check_server.mjs --stdio CMD [ARGS...]
//   node check_server.mjs --http URL [--token T]
//
// Prints one JSON object: {"tools": N, "results_checked": M, "problems": [...]};
// exits 1 when there is any problem. Run by tests/test_interop_typescript.py.
import { Client } from "@modelcontextprotocol/sdk/client/index.js";
import { StdioClientTransport } from "@modelcontextprotocol/sdk/client/stdio.js";
import { StreamableHTTPClientTransport } from "@modelcontextprotocol/sdk/client/streamableHttp.js";
import Ajv2020 from "ajv/dist/2020.js";

function transportFromArgs(argv) {
  if (argv[0] === "--stdio") {
    // The whole environment, so the server runs the same code as the test (PYTHONPATH).
    return new StdioClientTransport({ command: argv[1], args: argv.slice(2), stderr: "ignore",
                                      env: { ...process.env } });
  }
  if (argv[0] === "--http") {
    const token = argv[2] === "--token" ? argv[3] : undefined;
    const headers = token ? { Authorization: `Bearer ${token}` } : {};
    return new StreamableHTTPClientTransport(new URL(argv[1]), { requestInit: { headers } });
  }
  throw new Error("usage: check_server.mjs --stdio CMD ... | --http URL [--token T]");
}

// A short episode that reaches every structured tool at least once.
const SCRIPT = [
  ["load_scene", { scene_id: "cup_on_book" }],
  ["validate_action", { action: "move(book, on, shelf)" }],
  ["execute_actions", { actions: ["move(book, on, shelf)"] }],
  ["get_state", {}],
  ["execute_actions", { actions: ["move(cup, on, desk)", "move(book, on, shelf)", "done"] }],
  ["check_goal", {}],
  ["set_goal", { predicate: "single_stack" }],
  ["validate_plan", { scene_id: "cup_on_book", plan: "move(cup, desk)\nmove(book, shelf)" }],
  ["solve", { scene_id: "cup_on_book" }],
  ["end_episode", {}],
];

async function main() {
  const ajv = new Ajv2020({ strict: true, allowUnionTypes: true, validateFormats: false });
  const problems = [];
  const client = new Client({ name: "verigraph-interop-check", version: "1.0.0" });
  await client.connect(transportFromArgs(process.argv.slice(2)));
  const { tools } = await client.listTools();
  const outputValidators = new Map();
  for (const tool of tools) {
    try {
      ajv.compile(tool.inputSchema);
    } catch (error) {
      problems.push(`${tool.name}: inputSchema: ${error.message}`);
    }
    if (tool.outputSchema) {
      try {
        outputValidators.set(tool.name, ajv.compile(tool.outputSchema));
      } catch (error) {
        problems.push(`${tool.name}: outputSchema: ${error.message}`);
      }
    }
  }
  let episodeId;
  let checked = 0;
  for (const [name, args] of SCRIPT) {
    const withEpisode = episodeId && !("scene_id" in args) ? { episode_id: episodeId, ...args } : args;
    const result = await client.callTool({ name, arguments: withEpisode });
    if (result.isError) {
      problems.push(`${name}: tool error: ${result.content?.map((c) => c.text).join(" ")}`);
      continue;
    }
    if (name === "load_scene") episodeId = result.structuredContent.episode_id;
    const validate = outputValidators.get(name);
    if (validate && !validate(result.structuredContent)) {
      problems.push(`${name}: result does not match outputSchema: ${ajv.errorsText(validate.errors)}`);
    }
    if (validate) checked += 1;
  }
  await client.close();
  console.log(JSON.stringify({ tools: tools.length, results_checked: checked, problems }));
  process.exit(problems.length ? 1 : 0);
}

main().catch((error) => {
  console.log(JSON.stringify({ tools: 0, results_checked: 0, problems: [`client failed: ${error.message}`] }));
  process.exit(1);
});
