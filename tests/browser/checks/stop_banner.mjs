// stop_banner: waits for the STOP banner (after the hello, so a closed socket does not count)
// and reports its text; with --expect, the text must also contain that string.

import { waitForHello, waitInPage } from '../lib/page.mjs';

export async function run({ page, options, timeoutMs }) {
  await waitForHello(page, timeoutMs);
  const expect = options.expect ?? '';
  const what = expect ? `the STOP banner saying "${expect}"` : 'the STOP banner';
  const text = await waitInPage(page, what, (needle) => {
    const banner = document.getElementById('stop-banner');
    const open = document.getElementById('connection').dataset.state === 'open';
    return open && banner.dataset.state === 'stop' && banner.innerText.includes(needle) ? banner.innerText : null;
  }, expect, timeoutMs);
  return { text: text.replace(/\s+/g, ' ').trim() };
}
