// Starts the dashboard page: builds the panels, opens the socket, decodes each frame as it
// arrives and hands the message to the panels that show it. Drawing happens on animation frames
// (scene/view.js); the banner and the speed gauge are re-judged ten times a second and the plots
// four times.

import { BlendPanel, attachDropTarget } from './blend_panel.js';
import { CertificatesTable } from './certificates.js';
import { Connection } from './connection.js';
import { ViewControls } from './controls.js';
import { attachKeys, keyBindings, renderKeyHelp } from './keys.js';
import { Legend } from './legend.js';
import { readMessage } from './messages.js';
import { NodesTable } from './nodes_table.js';
import { PlotFeeds } from './plot_feeds.js';
import { TimeSeriesPlot } from './plots.js';
import { decodeFrame } from './protocol.js';
import { attachCameraControls } from './scene/camera_controls.js';
import { SceneView } from './scene/view.js';
import { SpeedGauge, speedGaugeState } from './speed_gauge.js';
import { StatusBar } from './status_bar.js';
import { StopBanner, bannerState } from './stop_banner.js';
import { StreamList } from './stream_list.js';
import { installTestHooks } from './test_hooks.js';
import { VerdictBook } from './verdicts.js';

const $ = (id) => document.getElementById(id);

const status = new StatusBar({
  connection: $('connection'), namespace: $('namespace'), frames: $('frames'),
  malformed: $('malformed'), serverError: $('server-error'),
});
const book = new VerdictBook();
const view = createView();
const connection = new Connection({ onFrame, onState });
const send = (message) => connection.send(message);
const controls = new ViewControls({
  toolbar: $('toolbar'), colorMode: $('color-mode'), pointSize: $('point-size'),
  pointSizeShown: $('point-size-shown'), pause: $('pause'), budget: $('point-budget'),
  budgetShown: $('point-budget-shown'), help: $('help'), helpButton: $('help-button'),
}, { view, send });
const blend = new BlendPanel({
  root: $('blend'), palette: $('palette'), sliders: $('blend-sliders'), result: $('blend-result'),
  commit: $('blend-commit'), clear: $('blend-clear'),
}, { send, pickPoint: (x, y) => (view ? view.pickPoint(x, y) : null) });
const plot = (name, unit) => new TimeSeriesPlot($(`plot-${name}`), $(`legend-${name}`), { unit });
const plots = {
  fit: plot('fit', 'ms'), latency: plot('latency', 'ms'), clearance: plot('clearance', 'm'),
  rates: plot('rates', 'Hz'), drops: plot('drops', '/s'),
};
const feeds = new PlotFeeds(plots);
const nodesTable = new NodesTable($('nodes-table'), $('nodes-summary'));
const certificates = new CertificatesTable($('certificates-body'));
const banner = new StopBanner($('stop-banner'));
const gauge = new SpeedGauge($('speed-gauge'));
const legend = new Legend($('legend'));
const streams = new StreamList($('streams'));
let hello = null; // the current connection's
let dashboardCounters = null;

const handlers = {
  hello: (message) => {
    hello = message;
    document.body.dataset.hello = 'received';
    book.onHello(hello);
    status.onHello(hello);
    controls.onHello(hello);
    blend.setBlend(hello.blend);
  },
  cloud: (cloud, nowMs) => {
    view?.setCloud(cloud);
    streams.onCloud(cloud, nowMs);
  },
  surrogate: (surrogate) => {
    view?.setSurrogate(surrogate);
    certificates.update(surrogate);
  },
  smooth: (smooth) => view?.setSmooth(smooth),
  arm: (arm) => view?.setArm(arm),
  verdict: (verdict, nowMs) => {
    book.record(verdict, nowMs);
    feeds.onVerdict(verdict, nowMs);
    view?.verdictArrived(verdict.arm);
  },
  nodes: (nodes, nowMs) => {
    nodesTable.update(nodes);
    feeds.onNodes(nodes, nowMs);
    dashboardCounters = nodes.dashboard;
  },
  blend_result: (result) => blend.onResult(result),
  error: (error) => status.showServerError(error.message),
};

// Never throws: a frame that cannot be read is counted and shown in the header.
function onFrame(data) {
  status.countFrame();
  let parsed;
  try {
    parsed = readMessage(decodeFrame(data));
  } catch (error) {
    status.countMalformed(error.message);
    return;
  }
  if (parsed === null) {
    status.countUnknown();
    return;
  }
  try {
    handlers[parsed.type](parsed.message, performance.now());
  } catch (error) {
    status.countMalformed(`${parsed.type} could not be shown: ${error.message}`);
  }
}

function onState(state) {
  status.setConnection(state);
  nodesTable.setConnected(state.state === 'open');
  if (state.state !== 'open') {
    hello = null; // the next connection sends its own
    delete document.body.dataset.hello;
  }
}

function createView() {
  try {
    const sceneView = new SceneView($('scene'), { freshVerdict: (arm) => book.fresh(arm, performance.now()) });
    attachCameraControls($('scene'), sceneView);
    sceneView.start();
    return sceneView;
  } catch (error) {
    $('gl-error').hidden = false;
    $('gl-error').textContent = error.message;
    return null;
  }
}

const bindings = keyBindings({ view, controls, blend });
attachKeys(bindings);
renderKeyHelp($('key-help'), bindings);
attachDropTarget($('viewport'), blend);
installTestHooks(view, () => hello);
controls.setColorMode('height');
connection.open();

setInterval(() => {
  const judged = { socketOpen: connection.isOpen, helloReceived: hello !== null, book, nowMs: performance.now() };
  banner.show(bannerState(judged));
  gauge.show(speedGaugeState(judged));
}, 100);
setInterval(() => {
  const nowMs = performance.now();
  for (const p of Object.values(plots)) p.draw(nowMs);
  status.refresh(dashboardCounters);
  streams.render(nowMs);
  if (view) legend.update(view.options.colorMode, view.points.streamColors(), view.points.heightRange());
}, 250);
