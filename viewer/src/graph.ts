// The scene graph as SVG: a layered layout (supports below what they carry), nodes
// coloured by role, the edges a step added highlighted, the ones it removed dashed.
import type { Edge, Graph, Role } from "./types";

const ROLE_COLORS: Record<Role["role"], string> = {
  fixed: "#9aa0a6", container: "#6fa8dc", surface: "#93c47d", object: "#f6b26b",
};
const SVG = "http://www.w3.org/2000/svg";
const key = (e: Edge) => `${e.source}|${e.relation}|${e.target}`;

function el(name: string, attrs: Record<string, string | number>, text?: string): SVGElement {
  const node = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  if (text !== undefined) node.textContent = text;
  return node;
}

function levels(graph: Graph): Map<string, number> {
  const support = new Map<string, string>();
  for (const e of graph.edges) if (e.relation !== "touches") support.set(e.source, e.target);
  const depth = new Map<string, number>();
  const visit = (id: string, seen: Set<string>): number => {
    if (depth.has(id)) return depth.get(id)!;
    const below = support.get(id);
    const d = below === undefined || seen.has(below) ? 0 : visit(below, new Set([...seen, id])) + 1;
    depth.set(id, d);
    return d;
  };
  for (const n of graph.nodes) visit(n.id, new Set());
  return depth;
}

export function drawGraph(graph: Graph, roles: Role[], added: Edge[], removed: Edge[],
                          blocking: string[]): SVGElement {
  const roleOf = new Map(roles.map((r) => [r.id, r.role]));
  const depth = levels(graph);
  const rows = new Map<number, string[]>();
  for (const n of graph.nodes) {
    const d = depth.get(n.id) ?? 0;
    rows.set(d, [...(rows.get(d) ?? []), n.id]);
  }
  const nLevels = Math.max(1, ...[...rows.keys()].map((d) => d + 1));
  const width = 480, rowH = 70, height = nLevels * rowH + 20, boxW = 86, boxH = 28;
  const pos = new Map<string, [number, number]>();
  const supportOf = new Map(graph.edges.filter((e) => e.relation !== "touches")
    .map((e) => [e.source, e.target]));
  for (const d of [...rows.keys()].sort((a, b) => a - b)) {
    const y = height - 30 - d * rowH;
    const ids = rows.get(d)!;
    if (d === 0) {
      ids.forEach((id, i) => pos.set(id, [((i + 0.5) / ids.length) * width, y]));
      continue;
    }
    // Above its support, siblings side by side, so a stack reads as a stack.
    const groups = new Map<string, string[]>();
    for (const id of ids) {
      const below = supportOf.get(id) ?? "";
      groups.set(below, [...(groups.get(below) ?? []), id]);
    }
    for (const [below, group] of groups) {
      const x = pos.get(below)?.[0] ?? width / 2;
      group.forEach((id, i) => pos.set(id, [
        Math.min(width - boxW / 2, Math.max(boxW / 2, x + (i - (group.length - 1) / 2) * (boxW + 10))),
        y]));
    }
  }
  const svg = el("svg", { viewBox: `0 0 ${width} ${height}`, width: "100%", role: "img",
                          "aria-label": "scene graph" });
  const defs = el("defs", {});
  for (const [id, color] of [["arrow", "#555"], ["arrow-hi", "#e8710a"], ["arrow-rm", "#c5221f"]]) {
    const marker = el("marker", { id, viewBox: "0 0 10 10", refX: 9, refY: 5, markerWidth: 7,
                                  markerHeight: 7, orient: "auto-start-reverse" });
    marker.appendChild(el("path", { d: "M0,0 L10,5 L0,10 z", fill: color }));
    defs.appendChild(marker);
  }
  svg.appendChild(defs);
  const addedKeys = new Set(added.map(key));
  const drawEdge = (e: Edge, kind: "normal" | "added" | "removed") => {
    const a = pos.get(e.source), b = pos.get(e.target);
    if (!a || !b) return;
    const color = kind === "added" ? "#e8710a" : kind === "removed" ? "#c5221f" : "#555";
    const marker = kind === "added" ? "arrow-hi" : kind === "removed" ? "arrow-rm" : "arrow";
    const line = el("line", { x1: a[0], y1: a[1] + boxH / 2, x2: b[0], y2: b[1] - boxH / 2,
      stroke: color, "stroke-width": kind === "added" ? 4 : 2,
      "marker-end": e.relation === "touches" ? "" : `url(#${marker})`,
      class: `edge edge-${kind}`, "data-edge": key(e) });
    if (kind === "removed") line.setAttribute("stroke-dasharray", "5 4");
    svg.appendChild(line);
    svg.appendChild(el("text", { x: (a[0] + b[0]) / 2 + 5, y: (a[1] + b[1]) / 2, "font-size": 11,
                                 fill: color }, e.relation));
  };
  for (const e of graph.edges) drawEdge(e, addedKeys.has(key(e)) ? "added" : "normal");
  for (const e of removed) drawEdge(e, "removed");
  for (const n of graph.nodes) {
    const [x, y] = pos.get(n.id)!;
    const role = roleOf.get(n.id) ?? "object";
    const g = el("g", { class: `node role-${role}`, "data-node": n.id });
    g.appendChild(el("rect", { x: x - boxW / 2, y: y - boxH / 2, width: boxW, height: boxH, rx: 5,
      fill: ROLE_COLORS[role], stroke: blocking.includes(n.id) ? "#c5221f" : "#333",
      "stroke-width": blocking.includes(n.id) ? 4 : 1 }));
    g.appendChild(el("text", { x, y: y + 4, "text-anchor": "middle", "font-size": 12 },
                     n.id.length > 13 ? n.id.slice(0, 12) + "…" : n.id));
    svg.appendChild(g);
  }
  return svg;
}

export function legend(): HTMLElement {
  const div = document.createElement("div");
  div.className = "legend";
  for (const [role, color] of Object.entries(ROLE_COLORS)) {
    const item = document.createElement("span");
    item.innerHTML = `<i style="background:${color}"></i>${role}`;
    div.appendChild(item);
  }
  const changed = document.createElement("span");
  changed.innerHTML = `<i style="background:#e8710a"></i>added edge`;
  div.appendChild(changed);
  return div;
}
