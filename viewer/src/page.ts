// The `verigraph view` page: paste or drop a scene, a plan and an optional goal; the
// local server checks them with the same tool functions and answers with the view.
import type { EpisodeView } from "./types";

const FIELDS: [string, string, string][] = [
  ["scene", "Scene graph (JSON or YAML), or a built-in scene id", "cup_on_book"],
  ["plan", "Plan (one action per line, or JSON)", "move(book, on, shelf)"],
  ["goal", "Goal (optional: JSON/YAML goal or graph, or a predicate)", ""],
];

export function startPage(root: HTMLElement, show: (view: EpisodeView) => void): void {
  const token = new URLSearchParams(location.hash.slice(1)).get("token") ?? "";
  const form = document.createElement("form");
  form.id = "input-form";
  const title = document.createElement("h1");
  title.textContent = "VeriGraph plan viewer";
  form.appendChild(title);
  for (const [name, label, placeholder] of FIELDS) {
    const wrap = document.createElement("label");
    wrap.textContent = label;
    const area = document.createElement("textarea");
    area.name = name;
    area.id = `field-${name}`;
    area.placeholder = placeholder;
    area.rows = name === "goal" ? 3 : 6;
    area.addEventListener("dragover", (e) => e.preventDefault());
    area.addEventListener("drop", async (e) => {
      e.preventDefault();
      const file = e.dataTransfer?.files[0];
      if (file) area.value = await file.text();
    });
    wrap.appendChild(area);
    form.appendChild(wrap);
  }
  const button = document.createElement("button");
  button.type = "submit";
  button.id = "check";
  button.textContent = "Check plan";
  const error = document.createElement("pre");
  error.id = "error";
  error.className = "error";
  form.append(button, error);
  const result = document.createElement("div");
  result.id = "result";
  root.replaceChildren(form, result);
  form.addEventListener("submit", async (e) => {
    e.preventDefault();
    error.textContent = "";
    const body: Record<string, string> = {};
    for (const [name] of FIELDS) body[name] = (form.elements.namedItem(name) as HTMLTextAreaElement).value;
    const response = await fetch("api/view", {
      method: "POST", body: JSON.stringify(body),
      headers: { "Content-Type": "application/json", Authorization: `Bearer ${token}` },
    });
    const answer = await response.json();
    if (!response.ok) {
      error.textContent = answer.error ?? `error ${response.status}`;
      result.replaceChildren();
      return;
    }
    show(answer as EpisodeView);
  });
}
