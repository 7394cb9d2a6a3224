// SPDX-License-Identifier: MIT
// Requests about the open map (src/latest.js): the answer used is the latest request's, for the map
// being opened or open, and only once that map is drawn; whichever order the answers come in, an
// older one's answer or error is dropped.
//
//   node --test test/
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { mapRequests } from '../src/latest.js';

// A promise settled by hand: [promise, resolve, reject].
function deferred() {
  let resolve, reject;
  const promise = new Promise((a, b) => { resolve = a; reject = b; });
  return [promise, resolve, reject];
}

// ask(id) answers with the promise given for that call; asked lists the ids asked.
function server(...answers) {
  const asked = [];
  return { asked, ask: (id) => { asked.push(id); return answers[asked.length - 1]; } };
}

test('an older answer that comes last does not overwrite the newer one; latest() says when one is no more', async () => {
  const requests = mapRequests();
  requests.opening('a')();
  const [slow, answerSlow] = deferred(), [fast, answerFast] = deferred();
  const s = server(slow, fast, new Promise(() => {}));
  const first = requests.run(s.ask);   // the profile first selected
  const second = requests.run(s.ask);  // then another one, answered first
  answerFast('profile B');
  answerSlow('profile A');
  const answer = await second;
  assert.deepEqual([answer.id, answer.value], ['a', 'profile B']);
  assert.equal(await first, null);
  assert.ok(answer.latest());
  requests.run(s.ask);  // a third, while the second's answer is read
  assert.equal(answer.latest(), false);
});

test('an error is thrown only for the latest request', async () => {
  const requests = mapRequests();
  requests.opening('a')();
  const [a, , failA] = deferred(), [b, , failB] = deferred();
  const s = server(a, b);
  const first = requests.run(s.ask), second = requests.run(s.ask);
  failA(new Error('old'));
  failB(new Error('new'));
  assert.equal(await first, null);
  await assert.rejects(second, /new/);
});

test('a request made while a map opens is for that map, and answered once it is drawn', async () => {
  const requests = mapRequests();
  requests.opening('old')();
  const drawn = requests.opening('new');  // its geometry not read yet
  assert.equal(requests.id, 'new');
  const [withMap, answerWithMap] = deferred(), [changed, answerChanged] = deferred();
  const s = server(withMap, changed);
  const asked = requests.run(s.ask);   // with the geometry
  const profile = requests.run(s.ask);  // the profile changed before the geometry came
  assert.deepEqual(s.asked, ['new', 'new']);
  answerChanged('profile B');
  answerWithMap('profile A');
  assert.equal(await asked, null);
  let answer = null;
  profile.then((a) => { answer = a; });
  await new Promise((resolve) => setTimeout(resolve, 0));
  assert.equal(answer, null, 'answered before the map was drawn');
  drawn();
  assert.deepEqual([(await profile).id, (await profile).value], ['new', 'profile B']);
});

test("another map opened drops the last map's requests, answered or failing", async () => {
  const requests = mapRequests();
  requests.opening('a')();
  const [a, answerA] = deferred(), [b, , failB] = deferred();
  const s = server(a, b);
  const first = requests.run(s.ask), second = requests.run(s.ask);
  requests.opening('b')();
  answerA(1);
  failB(new Error('gone'));
  assert.equal(await first, null);
  assert.equal(await second, null);
});

test('a request made outdated is aborted: by a later request, or by another map opened', async () => {
  const requests = mapRequests();
  requests.opening('a')();
  const signals = [];
  const ask = (id, signal) => {
    signals.push(signal);
    return new Promise((resolve, reject) => signal.addEventListener('abort', () => reject(signal.reason)));
  };
  const first = requests.run(ask);
  assert.equal(signals[0].aborted, false, 'the latest request is not aborted');
  const second = requests.run(ask);  // another profile chosen
  assert.equal(signals[0].aborted, true, "the older request's fetch goes on");
  assert.equal(signals[1].aborted, false);
  requests.opening('b');  // another map
  assert.equal(signals[1].aborted, true, "the last map's request goes on");
  assert.equal(await first, null);
  assert.equal(await second, null);
});

test('an answered request is not aborted while it is the latest, so its body can be read', async () => {
  const requests = mapRequests();
  requests.opening('a')();
  let signal = null;
  const answer = await requests.run((id, s) => { signal = s; return Promise.resolve('body'); });
  assert.equal(answer.value, 'body');
  assert.equal(signal.aborted, false);
  requests.run(() => new Promise(() => {}));
  assert.equal(signal.aborted, true, 'a later request aborts the reading of the last one');
  assert.equal(answer.latest(), false);
});
