// SPDX-License-Identifier: MIT
// When the page cannot start (the server refuses it, or is not there), a banner over the page
// says why and what to do, instead of a blank page. A station started with `--token` refuses a
// page opened without the token (401): the banner says where the token goes and takes it.
const TOKEN_KEY = 'sewerplan-token';  // api.js keeps the token for the tab under this key

export function showFatal(error) {
  let box = document.getElementById('fatal');
  if (!box) {
    box = Object.assign(document.createElement('div'), { id: 'fatal', role: 'alert' });
    document.body.prepend(box);
  }
  const line = (text) => Object.assign(document.createElement('p'), { textContent: text });
  if (error.status === 401) {
    const input = Object.assign(document.createElement('input'), { id: 'fatal-token', type: 'password', placeholder: 'token' });
    const use = Object.assign(document.createElement('button'), { id: 'fatal-use', textContent: 'Use this token' });
    use.onclick = () => {
      sessionStorage.setItem(TOKEN_KEY, input.value);
      location.reload();
    };
    box.replaceChildren(
      line(`The station refused this page: ${error.message}`),
      line('It was started with --token. Open the address `sewerplan serve` printed: it ends in ' +
           '#token=..., which gives this page the token. Or type the token here:'),
      input, use);
  } else {
    box.replaceChildren(line(`The station cannot start: ${error.message}`),
                        line('Check that `sewerplan serve` is running at this address, then reload the page.'));
  }
}
