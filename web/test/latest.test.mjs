// SPDX-License-Identifier: MIT
// The latest request only (src/latest.js): an answer that comes after a later request was started
// is dropped, whichever order the answers come in; errors likewise.
//
//   node --test test/
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { latestOnly } from '../src/latest.js';

// A promise settled by hand: [promise, resolve, reject].
function deferred() {
  let resolve, reject;
  const promise = new Promise((a, b) => { resolve = a; reject = b; });
  return [promise, resolve, reject];
}

test('an older answer that comes last does not overwrite the newer one; latest() says when one is no more', async () => {
  const requests = latestOnly();
  const [slow, answerSlow] = deferred(), [fast, answerFast] = deferred();
  const first = requests.run(slow);   // the profile first selected
  const second = requests.run(fast);  // then another one, answered first
  answerFast('profile B');
  answerSlow('profile A');
  const answer = await second;
  assert.equal(answer.value, 'profile B');
  assert.equal(await first, null);
  assert.ok(answer.latest());
  requests.run(new Promise(() => {}));  // a third, while the second's answer is read
  assert.equal(answer.latest(), false);
});

test('the latest answer is used whichever order they come in', async () => {
  const requests = latestOnly();
  const [a, answerA] = deferred(), [b, answerB] = deferred();
  const first = requests.run(a), second = requests.run(b);
  answerA(1);
  assert.equal(await first, null);
  answerB(2);
  assert.equal((await second).value, 2);
});

test('an error is thrown only for the latest request; drop() drops what is under way', async () => {
  const requests = latestOnly();
  const [a, , failA] = deferred(), [b, , failB] = deferred();
  const first = requests.run(a), second = requests.run(b);
  failA(new Error('old'));
  failB(new Error('new'));
  assert.equal(await first, null);
  await assert.rejects(second, /new/);
  const [c, answerC] = deferred();
  const third = requests.run(c);
  requests.drop();  // the map was closed
  answerC('late');
  assert.equal(await third, null);
});
