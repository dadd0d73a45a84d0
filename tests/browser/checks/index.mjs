// The checks dashboard_check.mjs can run, by name.

import * as dragPart from './drag_part.mjs';
import * as loads from './loads.mjs';
import * as nodeDies from './node_dies.mjs';
import * as plots from './plots.mjs';
import * as scene from './scene.mjs';
import * as screenshot from './screenshot.mjs';
import * as speedGauge from './speed_gauge.mjs';
import * as stopBanner from './stop_banner.mjs';

export const CHECKS = {
  loads: loads.run, scene: scene.run, plots: plots.run, node_dies: nodeDies.run,
  drag_part: dragPart.run, stop_banner: stopBanner.run, speed_gauge: speedGauge.run, screenshot: screenshot.run,
};
