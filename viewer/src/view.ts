// Lays out one EpisodeView: verdict, picture, graph, slider and the step list.
import { drawGraph, legend } from "./graph";
import type { EpisodeView, Step } from "./types";

function h<K extends keyof HTMLElementTagNameMap>(tag: K, cls?: string, text?: string
): HTMLElementTagNameMap[K] {
  const node = document.createElement(tag);
  if (cls) node.className = cls;
  if (text !== undefined) node.textContent = text;
  return node;
}

function stepItem(step: Step, select: () => void): HTMLLIElement {
  const li = h("li", `step ${step.ok ? "ok" : "refused"}`);
  li.dataset.step = String(step.step);
  li.tabIndex = 0;
  li.addEventListener("click", select);
  const head = h("div", "head");
  head.append(h("span", "mark", step.ok ? "✓" : "✗"), h("span", "num", `${step.step}`),
              h("code", "action", step.text));
  li.appendChild(head);
  const v = step.violation;
  if (v) {
    const detail = h("div", "detail");
    detail.append(h("span", "constraint", v.constraint), h("span", "message", ` ${v.message}`));
    li.appendChild(detail);
    if (v.blocking.length) li.appendChild(h("div", "blocking", `blocking: ${v.blocking.join(", ")}`));
    li.appendChild(h("div", "suggestion", `fix: ${v.suggestion}`));
  } else if (step.added.length || step.removed.length) {
    const change = [...step.removed.map((e) => `−${e.source} ${e.relation} ${e.target}`),
                    ...step.added.map((e) => `+${e.source} ${e.relation} ${e.target}`)];
    li.appendChild(h("div", "change", change.join("  ")));
  }
  return li;
}

export function showView(root: HTMLElement, view: EpisodeView): void {
  root.replaceChildren();
  const refused = view.steps.filter((s) => !s.ok).length;
  const verdict = h("div", `verdict ${view.valid ? "valid" : "invalid"}`);
  verdict.id = "verdict";
  verdict.textContent = `${view.valid ? "VALID" : "INVALID"} · ${view.steps.length} step(s)` +
    (refused ? ` · ${refused} refused` : "") +
    (view.not_checked ? ` · ${view.not_checked} not checked` : "") +
    (view.goal_summary ? ` · ${view.goal_summary}` : "");
  root.append(h("h1", "", `VeriGraph ${view.title}`), verdict);

  const main = h("div", "main");
  const left = h("section", "pictures");
  const img = h("img", "render");
  img.id = "render";
  img.alt = "scene drawing for the selected step";
  const caption = h("div", "caption");
  caption.id = "caption";
  const slider = h("input");
  slider.id = "slider";
  slider.type = "range";
  slider.min = "0";
  slider.max = String(view.steps.length);
  slider.setAttribute("aria-label", "step");
  const graphBox = h("div", "graph");
  graphBox.id = "graph";
  // Simulated episodes: the simulator's picture of each step follows the slider (a
  // server that sends only the current scene's render gets that, fixed).
  const perStep = Boolean(view.initial_scene_render);
  const sim = h("img", "scene-render");
  sim.id = "scene-render";
  const simNote = h("div", "caption");
  simNote.id = "scene-caption";
  if (perStep || view.scene_render) {
    const title = perStep ? "simulator" : "current scene (simulator)";
    if (!perStep) { sim.src = view.scene_render!; sim.alt = "simulator render of the current scene"; }
    left.append(h("h2", "", title), sim, simNote, h("h2", "", "scene graph, step by step"));
  }
  left.append(img, caption, slider, graphBox, legend());
  const list = h("ol", "steps");
  list.id = "steps";
  const right = h("section", "trace");
  right.append(h("h2", "", "steps"), list);
  main.append(left, right);
  root.appendChild(main);

  const items: HTMLLIElement[] = [];
  const select = (index: number) => {
    slider.value = String(index);
    const step = index > 0 ? view.steps[index - 1] : undefined;
    img.src = step?.render ?? view.initial_render;
    if (perStep) {
      const frame = step ? step.scene_render : view.initial_scene_render;
      sim.hidden = !frame;
      if (frame) sim.src = frame;
      sim.alt = step ? `simulator picture after step ${step.step}` : "simulator picture as loaded";
      simNote.hidden = Boolean(frame);
      simNote.textContent = frame ? "" : "no simulator picture for this step (only the first "
        + "steps are pictured)";
    }
    caption.textContent = step ? `after step ${step.step}: ${step.text}` +
      (step.ok ? "" : ` — refused (${step.violation?.constraint})`) : "initial scene";
    graphBox.replaceChildren(drawGraph(step?.graph ?? view.initial_graph, view.roles,
      step?.added ?? [], step?.removed ?? [], step?.outlined ?? []));
    items.forEach((li, i) => li.classList.toggle("selected", i === index - 1));
    root.dataset.selected = String(index);
  };
  view.steps.forEach((step, i) => {
    const li = stepItem(step, () => select(i + 1));
    items.push(li);
    list.appendChild(li);
  });
  if (view.not_checked) list.appendChild(h("li", "not-checked",
    `${view.not_checked} later action(s) not checked`));
  slider.addEventListener("input", () => select(Number(slider.value)));
  const firstRefused = view.steps.findIndex((s) => !s.ok);
  select(firstRefused >= 0 ? firstRefused + 1 : view.steps.length);
}
