// The JSON the Python side sends (verigraph.viewer.views.EpisodeView).
export interface Edge { source: string; relation: string; target: string;
  source_side?: number | null; target_side?: number | null }
export interface Graph { nodes: { id: string; label: string }[]; edges: Edge[] }
export interface Violation { constraint: string; message: string; blocking: string[];
  suggestion: string; step?: number | null }
export interface Step { step: number; text: string; ok: boolean; violation?: Violation | null;
  added: Edge[]; removed: Edge[]; outlined: string[]; graph: Graph; render?: string | null;
  scene_render?: string | null }
export interface Role { id: string; label: string; role: "fixed" | "container" | "surface" | "object" }
export interface EpisodeView {
  title: string; source: "plan" | "episode"; episode_id?: string | null; roles: Role[];
  initial_graph: Graph; initial_render: string; steps: Step[]; not_checked: number;
  valid: boolean; goal_reached: boolean | null; goal_summary?: string | null;
  scene_render?: string | null; initial_scene_render?: string | null;
}
